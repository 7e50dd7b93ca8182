#pragma once
// The parameters of the two hierarchies (bvh, spheretree), declared once: the builder's
// (builder, axis, bins, sbvh_alpha, sbvh_budget, leaf_size, ct, ci), the traversal order, and
// the BVH's node width.
#include "params.h"
#include "structures/bvh_build_types.h"

namespace accel {

/// The lecture's three ways to walk a hierarchy.
enum class TraversalOrder : uint8_t {
  Dfs,            ///< depth-first in tree order (left before right), whatever the ray's direction
  Ordered,        ///< depth-first, nearer child first; a popped node entered beyond the closest hit is skipped
  PriorityQueue,  ///< nodes in order of entry distance (lecture: p-queue); stops when the nearest
                  ///< pending node is farther than the closest hit
};

/// Everything a hierarchy's parameters set.
struct HierarchyOptions {
  BvhBuildOptions build;
  TraversalOrder traversal = TraversalOrder::Ordered;
  /// bvh only: children per stored node (2 binary, 4 wide SSE2, 8 wide AVX-512/AVX2/SSE2),
  /// or kAutoWidth (the default): 8 on a CPU with AVX2 (isa.h, capped by ACCEL_ISA), else 4.
  int width = kAutoWidth;
  static constexpr int kAutoWidth = 0;
  /// The width `width` stands for on this CPU.
  int resolved_width() const;
};

/// The declaration: builder parameters and `traversal`, plus `width` when `with_width`
/// (the bvh; the sphere tree has only the binary layout).
const ParamTable<HierarchyOptions>& hierarchy_param_table(bool with_width);
/// The options of validated hierarchy parameters (bvh's or spheretree's).
HierarchyOptions hierarchy_options(const ParamSet& params);

/// Builder parameters plus `traversal` (the sphere tree's list).
inline std::vector<ParamSpec> hierarchy_param_specs() { return hierarchy_param_table(false).specs(); }
/// The same plus `width` (the bvh's list).
inline std::vector<ParamSpec> bvh_param_specs() { return hierarchy_param_table(true).specs(); }

}  // namespace accel
