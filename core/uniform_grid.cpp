#include "uniform_grid.h"
