// The 8-wide BVH's AVX-512 kernels (wide_bvh_isa.h): the AVX2 source compiled with
// -mavx512f -mavx512vl -mavx512dq -mavx512bw -mavx512cd -ffp-contract=off
// (core/CMakeLists.txt), so the compiler may use the mask registers and the 32 vector
// registers; called only when the CPU has those extensions.
#define ACCEL_ISA_TAG Avx512Tag
#define ACCEL_ISA_SUFFIX avx512
#include "structures/wide_bvh_isa_unit.h"
