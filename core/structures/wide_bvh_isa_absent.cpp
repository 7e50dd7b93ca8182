// The AVX2 and AVX-512 kernels where the target has no AVX (WebAssembly): cpu_runs() is
// false for both there, so nothing calls these; they exist for the linker and stop loudly
// if that ever changes.
#include <cstdio>
#include <cstdlib>

#include "structures/wide_bvh_isa.h"

namespace accel {
namespace {
[[noreturn]] void no_avx(const char* what) {
  std::fprintf(stderr, "accelviz: internal error: %s called on a target without AVX\n", what);
  std::abort();
}
}  // namespace

Hit wide8_fast_avx2(const WideBvh8&, const Ray&) { no_avx("wide8_fast_avx2"); }
Hit wide8_fast_avx512(const WideBvh8&, const Ray&) { no_avx("wide8_fast_avx512"); }
void wide8_fast_batch_avx2(const WideBvh8&, const Ray*, size_t, Hit*) { no_avx("wide8_fast_batch_avx2"); }
void wide8_fast_batch_avx512(const WideBvh8&, const Ray*, size_t, Hit*) { no_avx("wide8_fast_batch_avx512"); }
int wide8_mask_avx2(const WideNode8&, const BoxTester&, float, float, float*, float*) { no_avx("wide8_mask_avx2"); }
int wide8_mask_avx512(const WideNode8&, const BoxTester&, float, float, float*, float*) { no_avx("wide8_mask_avx512"); }
Hit wide8_observed_avx2(const WideBvh8&, const Ray&, StepListener&) { no_avx("wide8_observed_avx2"); }
Hit wide8_observed_avx512(const WideBvh8&, const Ray&, StepListener&) { no_avx("wide8_observed_avx512"); }

}  // namespace accel
