#pragma once
// The instruction sets the wide BVH's traversal kernels are compiled for, and which one
// this process uses. The baseline (SSE2) is in every x86-64 CPU; the AVX2 and AVX-512
// kernels live in their own translation units, compiled with their flags
// (structures/wide_bvh_avx2.cpp, wide_bvh_avx512.cpp), and run only where the CPU has them.
// Environment variable ACCEL_ISA=sse2|avx2|avx512 caps the choice (CI forces sse2 to test
// the fallback on a CPU that has more).
#include <optional>
#include <string_view>

namespace accel {

enum class Isa : unsigned char { Sse2, Avx2, Avx512 };

/// Tag types the kernels are templated on: each instruction set's instantiations get
/// their own symbol names, so the linker can never pick an AVX-512 copy of a function for
/// the SSE2 path (tests/isa_symbols_test.sh checks the objects).
struct Sse2Tag {
  static constexpr Isa kIsa = Isa::Sse2;
};
struct Avx2Tag {
  static constexpr Isa kIsa = Isa::Avx2;
};
struct Avx512Tag {
  static constexpr Isa kIsa = Isa::Avx512;
};

/// "sse2", "avx2", "avx512".
const char* isa_name(Isa isa);
std::optional<Isa> parse_isa(std::string_view name);
/// True when this CPU (and OS) runs code compiled for `isa`: AVX2 needs avx2 and the OS
/// saving the ymm state; AVX-512 needs avx512f, vl, dq, bw and cd.
bool cpu_runs(Isa isa);
/// The best instruction set the CPU runs, capped by ACCEL_ISA when it is set (read once per
/// process; an unknown value is ignored with one line on stderr).
Isa active_isa();

}  // namespace accel
