#pragma once
// "Compare with the built-in": the same ray through a student's structure and the built-in
// structure of its kind, step by step, up to the first step where the two differ -- and
// which of the two answers is right (the double-precision reference). Node ids differ
// between two structures, so steps are compared by what the lecture shows of them: the box
// (or cell) entered, the triangle tested and its outcome, the closest hit taken, the answer.
// Pushes, pops and culls depend on the stack discipline and are not compared.
#include <string>
#include <vector>

#include "accuracy.h"
#include "structure.h"

namespace accel {

struct TraceDifference {
  bool differs = false;                 ///< false: every compared step agrees
  size_t mine_step = 0;                 ///< index into the student's recorded events (the viewer's step)
  size_t builtin_step = 0;              ///< index into the built-in's
  std::string mine_text, builtin_text;  ///< the two steps, described ("(ended)" past the last)
  Hit mine_hit, builtin_hit;
  ReferenceHit reference;
  HitVerdict mine_verdict = HitVerdict::Correct, builtin_verdict = HitVerdict::Correct;
  /// "yours: miss (false miss); built-in: triangle 9 at t=1.25 (right)".
  std::string answers_line() const;
  /// "first difference: your step 14, the built-in's step 14: ... / ..." or "no difference".
  std::string difference_line() const;
};

/// The parameters of the built-in `peer` that make it the lecture's plain version of its
/// kind (the BVH binary, median split, nearer child first), as key=value.
std::vector<std::string> builtin_compare_params(const std::string& peer);

/// Traces `ray` through both structures (built over `scene`) and compares their steps.
TraceDifference compare_with_builtin(const Scene& scene, const Ray& ray, const Structure& mine,
                                     const Structure& builtin);

}  // namespace accel
