#pragma once
// One-ulp steps of a float and the outward rounding of a double to float, as the builders'
// conservative bounds need them (the SBVH's clipped boxes, the kd-tree's perfect splits):
// std::nextafter without its library call, which was a twentieth of an SBVH build.
#include <cstdint>
#include <limits>

#include "bit_cast.h"

namespace accel {

/// The next float towards -inf: std::nextafter(f, -inf) for every float but NaN and -inf. A
/// float's bits, read as an integer, step one ulp away from zero when incremented and towards
/// it when decremented (one step from +inf is the largest finite float); +0 and -0 step to
/// the smallest negative denormal.
inline float step_down(float f) {
  if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
  const uint32_t bits = bit_cast<uint32_t>(f);
  return bit_cast<float>(f > 0.0f ? bits - 1 : bits + 1);
}
/// The next float towards +inf: std::nextafter(f, +inf) for every float but NaN and +inf.
inline float step_up(float f) { return -step_down(-f); }

/// The largest float <= d.
inline float float_down(double d) {
  const float f = float(d);
  return double(f) > d ? step_down(f) : f;
}
/// The smallest float >= d.
inline float float_up(double d) {
  const float f = float(d);
  return double(f) < d ? step_up(f) : f;
}

}  // namespace accel
