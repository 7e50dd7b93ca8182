#pragma once
// The one place that knows the structures: names as the CLI and viewer take them, what the
// front ends show of them (label, what a node is called, which pseudo code applies), their
// parameters, and a factory. Adding a structure means its files plus one entry in
// registry.cpp; no front end compares a structure's name to a literal.
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "build_trace.h"
#include "structure.h"

namespace accel {

/// Which of the lecture's traversal algorithms a structure runs: the front ends pick the
/// pseudo code by it (a hierarchy's listing further depends on its `traversal` parameter).
enum class TraversalFamily {
  Linear,     ///< test every triangle (brute force)
  Dda,        ///< 3D-DDA through grid cells (Amanatides & Woo 1987)
  Octree,     ///< recursion into the children hit, front to back
  KdTree,     ///< near/far recursion with t_split, cases (a)/(b)/(c)
  Hierarchy,  ///< bounding volume hierarchy: stack (dfs, ordered) or priority queue
};

/// Which of the lecture's constructions a structure runs: the front ends pick the
/// construction listing by it (a hierarchy's further depends on its `builder` parameter).
enum class ConstructionFamily {
  Linear,     ///< no subdivision: one list of every triangle (brute force)
  GridInsert, ///< the resolution rule, then every triangle into the cells it overlaps
  Octree,     ///< subdivide a cell into 8 equal children until the stopping criterion
  KdTree,     ///< choose an axis and a plane, distribute the triangles, recurse
  Hierarchy,  ///< one of the BVH builders (bvh_builders.h), by the `builder` parameter
};

/// One registered structure.
struct StructureInfo {
  std::string name;                 ///< "brute", "grid", ...: what --structure takes
  std::string label;                ///< for people: "uniform grid", "kd-tree", "sphere tree"
  std::string description;          ///< one line, in the lecture's terms
  std::string node_noun;            ///< what its nodes are called, plural: "cells", "nodes"
  TraversalFamily traversal = TraversalFamily::Linear;
  ConstructionFamily construction = ConstructionFamily::Linear;
  bool cells = false;               ///< nodes are the cells of one regular grid (empty ones can be drawn)
  bool reference = false;           ///< the brute-force oracle (the bench compares the others to it)
  std::vector<ParamSpec> params;    ///< what --param accepts
  /// A new, unbuilt structure for these (validated) parameters: a parameter may choose the
  /// class, e.g. the BVH's `width` picks the binary or the wide layout.
  std::function<std::unique_ptr<Structure>(const ParamSet&)> create;
  /// The pseudo code's traversal / construction variant for a structure without a
  /// `traversal` / `builder` parameter (a student's): "ordered", "median", ...
  std::string listing_traversal, listing_builder;
  /// A student's structure (student/accelviz_student.h, core/student/): built in from
  /// ACCEL_STUDENT_DIR, checked by `accelviz-cli check`.
  bool student = false;
  /// A student's: the built-in structure of the same lecture kind ("kdtree"), which the
  /// checks compare and time it against and the viewer's "compare with the built-in" runs.
  std::string builtin_peer;
  std::string source_file;  ///< a student's: the file that registered it
  bool optimized = true;    ///< a student's: that file was compiled with optimisation
};

/// All structures, in lecture order, then the students' (in the order their names sort).
const std::vector<StructureInfo>& structure_registry();
/// Names of all structures, in lecture order.
std::vector<std::string> structure_names();
/// The student structures built in (empty without ACCEL_STUDENT_DIR).
std::vector<const StructureInfo*> student_structures();
/// The entry for `name`, or an Error listing the valid names.
Result<const StructureInfo*> find_structure(const std::string& name);

/// A structure chosen by name with its parameters, validated together: what every front end
/// makes of a name and `key=value` strings.
struct StructureChoice {
  const StructureInfo* info = nullptr;
  ParamSet params;
};
/// The entry for `name` and its parameters parsed from `key=value` strings; errors name the
/// structure (listing the valid ones) or the parameter and its valid range.
Result<StructureChoice> parse_structure(const std::string& name, const std::vector<std::string>& params);

/// The class the parameters ask for, unbuilt, with its kernel set (Kernel::Planar over a 2D
/// scene, whatever `kernel` says): build_structure()'s first half, for a caller that sets
/// the structure up before its build (the viewer's replay of a student's failed build).
std::unique_ptr<Structure> create_structure(const StructureInfo& info, const Scene& scene, const ParamSet& params,
                                            Kernel kernel = Kernel::Watertight);

/// The one way the CLI, the bench, the tests and the viewer build a structure: create
/// the class the parameters ask for, set the kernel (create_structure()), build. Errors
/// name the parameter or the internal limit. `control` (optional) reports progress and can
/// cancel the build (then the error is cancelled_error()). With a `recorder` the build is recorded step by
/// step (Structure::build_recorded()).
Result<std::unique_ptr<Structure>> build_structure(const StructureInfo& info, const Scene& scene,
                                                   const ParamSet& params, Kernel kernel = Kernel::Watertight,
                                                   BuildControl* control = nullptr,
                                                   BuildRecorder* recorder = nullptr);
/// A build recorded for playback: the structure (exactly the one build_structure() makes),
/// its construction steps and how many recordings they took.
struct RecordedBuild {
  std::unique_ptr<Structure> structure;
  BuildTrace trace;
  std::vector<RecordAttempt> attempts;
};
/// Builds with every construction step recorded, keeping the steps within `budget_bytes`:
/// when they do not fit, it records again with the depth limit halved (from the deepest node
/// the builder made) until they do, so the top levels are complete and trace.coverage()
/// says "recorded to depth D of E". Builders whose steps have no depth (bottom-up merges)
/// keep the first steps that fit ("stopped at the step budget after K steps"). The first
/// recording stops at `first_depth_limit` (the viewer's: recording_first_depth_limit()).
Result<RecordedBuild> build_structure_recorded(const StructureInfo& info, const Scene& scene, const ParamSet& params,
                                               Kernel kernel = Kernel::Watertight,
                                               size_t budget_bytes = BuildRecorder::kDefaultBudgetBytes,
                                               BuildControl* control = nullptr,
                                               int first_depth_limit = std::numeric_limits<int>::max());

/// The same from `key=value` strings, validated first (errors name the structure or the
/// parameter and its valid range).
Result<std::unique_ptr<Structure>> build_structure(const std::string& name, const Scene& scene,
                                                   const std::vector<std::string>& params,
                                                   Kernel kernel = Kernel::Watertight,
                                                   BuildControl* control = nullptr,
                                                   BuildRecorder* recorder = nullptr);

}  // namespace accel
