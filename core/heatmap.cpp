#include "heatmap.h"
