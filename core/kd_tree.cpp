#include "kd_tree.h"
