#include "isa.h"

#include <cstdio>
#include <cstdlib>

namespace accel {

const char* isa_name(Isa isa) {
  switch (isa) {
    case Isa::Sse2: return "sse2";
    case Isa::Avx2: return "avx2";
    case Isa::Avx512: return "avx512";
  }
  return "?";
}

std::optional<Isa> parse_isa(std::string_view name) {
  for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512})
    if (name == isa_name(isa)) return isa;
  return std::nullopt;
}

bool cpu_runs(Isa isa) {
#if !defined(__x86_64__) && !defined(__i386__)
  // WebAssembly: the SSE2 kernels run on its 128-bit SIMD (emscripten's SSE headers); no AVX.
  return isa == Isa::Sse2;
#else
  switch (isa) {
    case Isa::Sse2: return true;
    // __builtin_cpu_supports also checks that the OS enabled the registers' state (XCR0).
    case Isa::Avx2: return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
    case Isa::Avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("popcnt");
  }
  return false;
#endif
}

namespace {
Isa detect() {
  Isa best = Isa::Sse2;
  for (Isa isa : {Isa::Avx2, Isa::Avx512})
    if (cpu_runs(isa)) best = isa;
  if (const char* cap = std::getenv("ACCEL_ISA"); cap && *cap) {
    if (const auto wanted = parse_isa(cap)) {
      if (*wanted < best) best = *wanted;
    } else {
      std::fprintf(stderr, "ACCEL_ISA=%s ignored: expected sse2, avx2 or avx512\n", cap);
    }
  }
  return best;
}
}  // namespace

Isa active_isa() {
  static const Isa isa = detect();
  return isa;
}

}  // namespace accel
