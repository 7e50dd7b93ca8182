#pragma once
// The lecture's pseudo code of each traversal, and which of its lines a recorded trace
// event corresponds to, so the viewer can highlight "where we are" in the code while the
// animation plays. GL-free (unit-tested without a window).
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "build_trace.h"
#include "registry.h"
#include "structure.h"
#include "structures/bvh_build_types.h"

namespace viz {

/// The traversals the viewer has pseudo code for.
enum class TraversalKind {
  Brute,             ///< a loop over all triangles
  Grid,              ///< 3D-DDA (lecture: Amanatides & Woo loop)
  Grid2d,            ///< the same over a 2D scene: the lecture's 2D DDA (X, Y)
  Octree,            ///< lecture: OctreeNode::Trace
  KdTree,            ///< lecture: traverse(r, n, t_min, t_max), cases (a)/(b)/(c)
  HierarchyDfs,      ///< BVH / sphere tree: stack, tree order
  HierarchyOrdered,  ///< BVH / sphere tree: stack, nearer child first
  HierarchyPqueue,   ///< BVH / sphere tree: the lecture's priority-queue loop
  Unknown,
};

/// The kind for a structure's traversal family (accel::StructureInfo::traversal) and its
/// `traversal` parameter ("" when it has none).
TraversalKind traversal_kind(accel::TraversalFamily family, const std::string& traversal);
/// Short label, e.g. "priority queue".
const char* traversal_label(TraversalKind kind);

/// One pseudo-code listing.
struct PseudoCode {
  std::string title;               ///< e.g. "kd-tree: traverse (lecture)"
  std::vector<std::string> lines;  ///< the code, one entry per line
  std::vector<std::string> anchors;  ///< per line: the name events map to ("" = none)
};

/// The listing of `kind`.
const PseudoCode& pseudo_code(TraversalKind kind);

/// How the mapping may look at nodes other than through the events: the view of a node or
/// cell (NodeView::leaf, box). May be empty; then leaves are told by the next event.
using NodeLookup = std::function<accel::NodeView(accel::NodeId)>;

/// The line (index into pseudo_code(kind).lines) of events[step], or -1 when it has none.
int pseudo_code_line(TraversalKind kind, std::span<const accel::TraceEvent> events, size_t step,
                     const NodeLookup& lookup);

/// The anchor name of events[step] (what pseudo_code_line looks up), for tests.
std::string pseudo_code_anchor(TraversalKind kind, std::span<const accel::TraceEvent> events, size_t step,
                               const NodeLookup& lookup);

// ---------------------------------------------------------------------------------------
// Construction (the construction mode's panel)

/// The construction a listing is shown for: the structure's construction family and, for
/// the hierarchies, their builder -- keyed by the core's accel::BvhBuilderKind, whose table
/// (bvh_builders.h) names the builders, so no list of them is kept here.
struct BuildCodeKind {
  bool known = false;
  accel::ConstructionFamily family = accel::ConstructionFamily::Linear;
  accel::BvhBuilderKind builder = accel::BvhBuilderKind::BinnedSah;  ///< family Hierarchy only
  /// No construction known (an unknown structure or invalid parameters).
  static const BuildCodeKind Unknown;
  bool operator==(const BuildCodeKind&) const = default;
};
inline const BuildCodeKind BuildCodeKind::Unknown{};

/// The kind of a family without builders (Linear, GridInsert, Octree, KdTree).
BuildCodeKind build_code_of(accel::ConstructionFamily family);
/// The kind of a hierarchy built by `builder`.
BuildCodeKind build_code_of(accel::BvhBuilderKind builder);

/// The construction of structure `name` with its `params` (key=value; the builder and
/// split parameters choose the listing, defaults as the registry's).
BuildCodeKind build_code_kind(const std::string& name, const std::vector<std::string>& params);
/// Short label, e.g. "binned SAH" (a builder's: its row's label).
const char* build_code_label(BuildCodeKind kind);
/// The listing of `kind`; its anchors are build_event_kind_name()s (leaves: "leaf"). A
/// builder without a listing of its own gets the "no listing" one.
const PseudoCode& build_pseudo_code(BuildCodeKind kind);
/// The line of step `e` in build_pseudo_code(kind), or -1 when it has none (nullptr: -1).
int build_code_line(BuildCodeKind kind, const accel::BuildEvent* e);

}  // namespace viz
