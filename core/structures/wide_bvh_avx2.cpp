// The 8-wide BVH's AVX2 kernels (wide_bvh_isa.h). Compiled with -mavx2 -ffp-contract=off
// (core/CMakeLists.txt); called only when the CPU has AVX2.
#define ACCEL_ISA_TAG Avx2Tag
#define ACCEL_ISA_SUFFIX avx2
#include "structures/wide_bvh_isa_unit.h"
