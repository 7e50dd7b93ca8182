#include "sphere_tree.h"
