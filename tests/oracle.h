#pragma once
// The oracle of the tests: core/accuracy.h's docs/hits.md rule with a readable reason.
#include <string>

#include "accuracy.h"

namespace accel::testing {

using accel::ReferenceHit;
using accel::reference_closest;

/// True when `got` is a correct answer for `ray` by docs/hits.md's rule; otherwise `why` says why.
inline bool hit_is_correct(const Scene& scene, const Ray& ray, const Hit& got, const ReferenceHit& ref,
                           std::string* why = nullptr) {
  const HitVerdict v = judge_hit(scene, ray, got, ref);
  if (v == HitVerdict::Correct) return true;
  if (why)
    *why = std::string(verdict_name(v)) + " (got prim " + std::to_string(got.prim) + " t " + std::to_string(got.t) +
           ", ref prim " + std::to_string(ref.prim) + " t " + std::to_string(ref.t) + ")";
  return false;
}

}  // namespace accel::testing
