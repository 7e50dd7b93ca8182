#include "bvh.h"
