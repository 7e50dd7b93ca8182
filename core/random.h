#pragma once
// A tiny deterministic generator (SplitMix64, Steele et al. 2014). Used instead of <random>
// distributions, whose output differs between standard libraries, so procedural scenes and
// ray sets are the same on every machine.
#include <array>
#include <cstdint>

namespace accel {

class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  uint64_t next_u64() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1) with 24 random bits (exact in float).
  float uniform() { return float(next_u64() >> 40) * 0x1.0p-24f; }
  /// Uniform in [lo, hi).
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  /// A point's x, y and z, each uniform in [lo, hi), drawn z first, then y, then x. Never
  /// write Vec3(rng.uniform(), rng.uniform(), rng.uniform()): C++ leaves the order of a
  /// call's arguments open, GCC drew those right to left and clang left to right, so the
  /// native build and the web page (emscripten is clang) made different scenes and rays.
  /// This order is GCC's, so the scenes and ray sets made before stay the same.
  std::array<float, 3> uniform_xyz(float lo = 0.0f, float hi = 1.0f) {
    const float z = uniform(lo, hi);
    const float y = uniform(lo, hi);
    const float x = uniform(lo, hi);
    return {x, y, z};
  }

 private:
  uint64_t state_;
};

}  // namespace accel
