#pragma once
// "Compare with the built-in": the same ray through a student's structure and the built-in
// structure of its kind set up like it (the split rule, the axis rule and the leaf size read
// from the student's build log: core/student/waste.h), and which of the two answers is right
// (the double-precision reference). The walks are compared by what they mean, never by their
// boxes (two trees with other split planes differ at once without either being wrong): the
// first false claim of the student's walk (core/student/walk_audit.h), else the nearest hit
// one walk tests and the other never does, else the answer kept; the triangles each tests.
#include <string>
#include <vector>

#include "accuracy.h"
#include "structure.h"

namespace accel {

struct TraceDifference {
  bool differs = false;                 ///< false: every compared step agrees
  size_t mine_step = 0;                 ///< index into the student's recorded events (the viewer's step)
  size_t builtin_step = 0;              ///< index into the built-in's
  std::string mine_text, builtin_text;  ///< what each walk did there
  size_t mine_tests = 0, builtin_tests = 0;  ///< triangles tested
  Hit mine_hit, builtin_hit;
  ReferenceHit reference;
  HitVerdict mine_verdict = HitVerdict::Correct, builtin_verdict = HitVerdict::Correct;
  /// "yours: miss (false miss); built-in: triangle 9 at t=1.25 (right)".
  std::string answers_line() const;
  /// "first difference: your step 14, the built-in's step 14: ... / ..." or "no difference".
  std::string difference_line() const;
};

/// The parameters of the built-in `peer` that set it up like `mine` (a student's structure:
/// its split rule, axis rule and leaf size from its build log), else the lecture's plain
/// version of its kind (the BVH binary, median split, nearer child first), as key=value.
std::vector<std::string> builtin_compare_params(const std::string& peer, const Structure* mine = nullptr,
                                                const Scene* scene = nullptr);

/// Traces `ray` through both structures (built over `scene`) and compares what they do.
TraceDifference compare_with_builtin(const Scene& scene, const Ray& ray, const Structure& mine,
                                     const Structure& builtin);

}  // namespace accel
