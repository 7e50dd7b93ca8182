#pragma once
// What a right structure wastes against the built-in structure of its kind set up like it
// (the split rule, the leaf size, the grid's cells: read from its build log). check reports
// it in a sentence each, with the lecture's reason; --strict fails past the limits a
// lecturer sets. Correctness stays the default verdict: waste never fails a structure
// without --strict.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "accelviz_student.h"
#include "scene.h"

namespace accel {

struct KitTree;

/// --limit NAME=VALUE: past these, --strict fails the structure (0: no limit).
struct WasteLimits {
  double uncrossed = 0.25;   ///< share of visited nodes or cells the ray does not cross
  double triangles = 3.0;    ///< triangles tested per ray, as a multiple of the built-in's
  double leaf_size = 4.0;    ///< mean triangles per leaf, as a multiple of the built-in's
  double references = 3.0;   ///< references per triangle, as a multiple of the built-in's
};
/// Sets `name` (uncrossed, triangles, leaf_size, references) from "NAME=VALUE"; an error
/// message naming the option otherwise ("" when it was set).
std::string set_waste_limit(WasteLimits& limits, const std::string& name_value);

/// Counts over the right answers of the cases measured (the procedural ones).
struct WasteTally {
  size_t rays = 0, visits = 0, uncrossed = 0;
  size_t kd_inner = 0, kd_far_only = 0, kd_needs_far_only = 0;
  double tris = 0, peer_tris = 0;  ///< triangle tests, summed over `rays`
  double leaves = 0, leaf_refs = 0, peer_leaves = 0, peer_leaf_refs = 0;
  double refs = 0, peer_refs = 0, prims = 0;
  std::string peer_setup;  ///< "split=middle leaf_size=4", the last case's
  void add(const WasteTally& o);
};

struct WasteFinding {
  std::string name;      ///< a WasteLimits name
  double value = 0;      ///< the student's (a share, or a multiple of the built-in's)
  double limit = 0;
  std::string sentence;  ///< with the lecture's reason
  bool over = false;     ///< past the limit
};

struct WasteReport {
  bool measured = false;
  std::string peer;  ///< "kdtree split=middle leaf_size=4"
  std::vector<WasteFinding> findings;  ///< only what exceeds the built-in by a margin worth saying
  bool over_limit = false;             ///< --strict and some finding past its limit
};

/// The built-in's parameters that set it up like the student's tree: key=value pairs.
std::vector<std::pair<std::string, std::string>> peer_setup_like(const KitTree& tree, accelviz::Kind kind,
                                                                 const Scene& scene);
/// The findings of `tally` for a structure of `kind` compared with `peer`.
WasteReport waste_report(const WasteTally& tally, accelviz::Kind kind, const std::string& peer,
                         const WasteLimits& limits, bool strict);

}  // namespace accel
