#pragma once
// The body of one ISA unit (wide_bvh_avx2.cpp, wide_bvh_avx512.cpp): the 8-lane slab test
// and the entry points of wide_bvh_isa.h, for the tag ACCEL_ISA_TAG and the name suffix
// ACCEL_ISA_SUFFIX. Included only by those two files, which CMake compiles with their
// instruction set's flags and -ffp-contract=off.
#include <immintrin.h>

#include "structures/wide_bvh_isa.h"

#ifndef ACCEL_ISA_TAG
#error "define ACCEL_ISA_TAG (Avx2Tag or Avx512Tag) and ACCEL_ISA_SUFFIX before including this file"
#endif
#define ACCEL_ISA_CAT2(a, b) a##b
#define ACCEL_ISA_CAT(a, b) ACCEL_ISA_CAT2(a, b)
#define ACCEL_ISA_NAME(base) ACCEL_ISA_CAT(base, ACCEL_ISA_SUFFIX)

namespace accel {

/// Per-ray constants of the 8-lane slab test (one ymm register per coordinate).
template <>
struct WideRayFor<ACCEL_ISA_TAG> {
  explicit WideRayFor(const BoxTester& box_ray) {
    for (int axis = 0; axis < 3; ++axis) {
      org[axis] = _mm256_set1_ps(box_ray.org[axis]);
      inv_dir[axis] = _mm256_set1_ps(box_ray.inv_dir[axis]);
      inv_dir_far[axis] = _mm256_set1_ps(box_ray.inv_dir_far[axis]);
      // Byte offsets of the near and far rows in an 8-wide node (32 bytes a row): one
      // address addition per load in the loop, no index scaling.
      near_off[axis] = size_t(box_ray.near_index[axis]) * sizeof(WideNode8::bounds[0]);
      far_off[axis] = size_t(box_ray.far_index[axis]) * sizeof(WideNode8::bounds[0]);
    }
  }
  __m256 org[3], inv_dir[3], inv_dir_far[3];
  size_t near_off[3], far_off[3];
};

/// intersect_four() of wide_bvh.h on all eight slots at once: the same operations in the
/// same order per lane (subtract, multiply by the inverse direction, or by its widened form
/// for the far distance, max / min with the running interval; vmaxps/vminps return the
/// second operand on NaN as maxps/minps do; the comparison is ordered like cmpleps), so the
/// mask and the distances are the SSE2 kernel's bit for bit (tests/test_wide_isa.cpp).
ACCEL_FORCE_INLINE int intersect_children(const WideNode8& node, const WideRayFor<ACCEL_ISA_TAG>& r, float tmin,
                                          float tmax, float* t_enter, float* t_exit) {
  __m256 t0 = _mm256_set1_ps(tmin), t1 = _mm256_set1_ps(tmax);
  const char* rows = reinterpret_cast<const char*>(node.bounds);
  for (int axis = 0; axis < 3; ++axis) {
    const __m256 lo = _mm256_load_ps(reinterpret_cast<const float*>(rows + r.near_off[axis]));
    const __m256 hi = _mm256_load_ps(reinterpret_cast<const float*>(rows + r.far_off[axis]));
    const __m256 t_near = _mm256_mul_ps(_mm256_sub_ps(lo, r.org[axis]), r.inv_dir[axis]);
    const __m256 t_far = _mm256_mul_ps(_mm256_sub_ps(hi, r.org[axis]), r.inv_dir_far[axis]);
    t0 = _mm256_max_ps(t_near, t0);
    t1 = _mm256_min_ps(t_far, t1);
  }
  _mm256_store_ps(t_enter, t0);
  _mm256_store_ps(t_exit, t1);
  return _mm256_movemask_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ));
}

/// nearer_slots() of wide_bvh.h on all eight slots in one compare each: the same ordered
/// less-than and equality per lane, so the same ranks.
ACCEL_FORCE_INLINE int nearer_slots(ACCEL_ISA_TAG, std::integral_constant<int, 8>, const float* t0, int s) {
  const __m256 t = _mm256_load_ps(t0);
  const __m256 key = _mm256_broadcast_ss(t0 + s);
  const int lt = _mm256_movemask_ps(_mm256_cmp_ps(t, key, _CMP_LT_OQ));
  const int eq = _mm256_movemask_ps(_mm256_cmp_ps(t, key, _CMP_EQ_OQ));
  return lt | (eq & ((1 << s) - 1));
}

Hit ACCEL_ISA_NAME(wide8_fast_)(const WideBvh8& bvh, const Ray& ray) {
  NullSink sink;
  return bvh.traverse_with<ACCEL_ISA_TAG>(ray, sink);
}

// Flattened: the traversal is inlined into the loop, so its entry and exit (register saves,
// the stack frame's alignment) are paid once a batch, not once a ray. Not by inlining
// traverse_with itself: its SSE2 copy would then make every WideBvhOf::traverse() call pay
// that frame before it even calls the fast path.
__attribute__((flatten)) void ACCEL_ISA_NAME(wide8_fast_batch_)(const WideBvh8& bvh, const Ray* rays, size_t n,
                                                                Hit* hits) {
  NullSink sink;
  for (size_t i = 0; i < n; ++i) hits[i] = bvh.traverse_with<ACCEL_ISA_TAG>(rays[i], sink);
}

int ACCEL_ISA_NAME(wide8_mask_)(const WideNode8& node, const BoxTester& ray, float tmin, float tmax, float* t0,
                                float* t1) {
  alignas(32) float a[8], b[8];
  const int mask = intersect_children(node, WideRayFor<ACCEL_ISA_TAG>(ray), tmin, tmax, a, b);
  for (int s = 0; s < 8; ++s) {
    t0[s] = a[s];
    t1[s] = b[s];
  }
  return mask;
}

Hit ACCEL_ISA_NAME(wide8_observed_)(const WideBvh8& bvh, const Ray& ray, StepListener& listener) {
  ForwardingSink sink{&listener};
  return bvh.traverse_with<ACCEL_ISA_TAG>(ray, sink);
}

}  // namespace accel
