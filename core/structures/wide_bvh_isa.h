#pragma once
// The 8-wide BVH's kernels per instruction set, behind plain functions: the AVX2 and
// AVX-512 ones are compiled in their own translation units (wide_bvh_avx2.cpp,
// wide_bvh_avx512.cpp, with -mavx2 / -mavx512*), and only called when the CPU runs them
// (isa.h). Everything these units instantiate is named by their ISA tag, so no inline
// function compiled for AVX-512 can stand in for the SSE2 one (tests/isa_symbols_test.sh).
#include "geometry.h"
#include "isa.h"
#include "structures/wide_bvh.h"
#include "trace.h"

namespace accel {

/// The fast traversal for `isa`, one ray and a batch (both nullptr for Sse2: the template
/// path is the fast path).
struct FastWidePaths {
  FastWideTraversal one = nullptr;
  FastWideBatch batch = nullptr;
};
FastWidePaths fast_wide8_paths(Isa isa);

/// For tests: the 8-wide box test of `isa` on one node, as the traversal runs it: returns
/// the hit mask (bit s = slot s) and writes each slot's [t_enter, t_exit].
int wide8_children_mask(Isa isa, const WideNode8& node, const BoxTester& ray, float tmin, float tmax,
                        float t_enter[8], float t_exit[8]);
/// For tests: the whole traversal with the kernels of `isa`, every step reported.
Hit wide8_traverse_observed(Isa isa, const WideBvh8& bvh, const Ray& ray, StepListener& listener);

// Defined by each ISA unit (the same source, wide_bvh_isa_unit.h, with its tag).
Hit wide8_fast_avx2(const WideBvh8& bvh, const Ray& ray);
Hit wide8_fast_avx512(const WideBvh8& bvh, const Ray& ray);
void wide8_fast_batch_avx2(const WideBvh8& bvh, const Ray* rays, size_t n, Hit* hits);
void wide8_fast_batch_avx512(const WideBvh8& bvh, const Ray* rays, size_t n, Hit* hits);
int wide8_mask_avx2(const WideNode8& node, const BoxTester& ray, float tmin, float tmax, float* t0, float* t1);
int wide8_mask_avx512(const WideNode8& node, const BoxTester& ray, float tmin, float tmax, float* t0, float* t1);
Hit wide8_observed_avx2(const WideBvh8& bvh, const Ray& ray, StepListener& listener);
Hit wide8_observed_avx512(const WideBvh8& bvh, const Ray& ray, StepListener& listener);

}  // namespace accel
