#pragma once
// The BVH builders' data, shared by the hierarchies (hierarchy.h, wide_bvh.h) and the builders
// (bvh_builders.h): the options, the binary tree every builder produces, and the entry point
// build_bvh_tree() that runs the builder the options name -- so the structures' headers hold
// no builder.
#include <cstdint>
#include <string>
#include <vector>

#include "build_control.h"
#include "build_trace.h"
#include "scene.h"
#include "vec_math.h"

namespace accel {

/// The builders, one row each in bvh_builders.cpp's table (name, label, help, build function).
enum class BvhBuilderKind : uint8_t {
  Median,     ///< sort centres, split at the median (lecture: top-down, "median"): bvh_median_builder.h
  Sah,        ///< full sweep over sorted centroids on all three axes (MacDonald & Booth 1990): bvh_sweep_builder.h
  BinnedSah,  ///< binned SAH approximation (Wald 2007, "On fast construction of SAH-based BVHs"): bvh_binned_builder.h
  PcaSah,     ///< sweep along the principal axis of the centroids (lecture: "PCA", then SAH plane sweep): bvh_pca_builder.h
  BottomUp,   ///< agglomerative clustering, locally ordered (Meister & Bittner 2018, "PLOC"): bvh_ploc_builder.h
  Insertion,  ///< incremental insertion by least surface-area cost (Goldsmith & Salmon 1987): bvh_insertion_builder.h
  Sbvh,       ///< binned SAH plus spatial splits (Stich, Friedrich & Dietrich 2009, "SBVH"): bvh_spatial_builder.h
};

/// Axis rule of the median builder.
enum class MedianAxis : uint8_t { X, RoundRobin, Longest };

/// Builder options, as the hierarchies' parameters set them (hierarchy_params.h).
struct BvhBuildOptions {
  /// Binned SAH by default: on the 16 shared meshes its SAH cost is that of the full sweep
  /// (within 1% on 13, better on 9; docs in bench/README.md) at a fraction of its build time.
  BvhBuilderKind builder = BvhBuilderKind::BinnedSah;
  MedianAxis axis = MedianAxis::Longest;
  /// 64 bins (Embree uses 32): with 16 or 32 the binned cost exceeds the sweep's by 2-5% on
  /// crytek_sponza and spider; a node of n references uses at most 4 + n / 4 bins anyway.
  int bins = 64;
  int leaf_size = 4;     ///< max triangles per leaf
  /// sbvh: a node tries a spatial split when its best object split's children overlap by
  /// more than this fraction of the root's surface area (Stich et al.'s alpha).
  double sbvh_alpha = 1e-5;
  /// sbvh: at most this many references per triangle over the whole tree (1: object splits
  /// only). The budget is handed down, split between the children by their reference
  /// counts, so the tree does not depend on the build order.
  float sbvh_budget = 1.5f;
  float ct = 1.0f;       ///< SAH cost of one traversal step
  float ci = 1.0f;       ///< SAH cost of one ray/triangle test
  /// Triangles one test handles: 1 for the binary tree's scalar test, 4 for the 4-wide
  /// layout's SSE leaf test, where a leaf of 4 costs what a leaf of 1 costs.
  int prims_per_test = 1;
  /// SAH cost of testing a leaf of n triangles.
  float leaf_cost(size_t n) const { return ci * float((n + size_t(prims_per_test) - 1) / size_t(prims_per_test)); }
};

/// One node of the builder's output. Leaves have count > 0 and cover
/// prims[first, first + count); inner nodes have count == 0 and two children.
struct BuildNode {
  Aabb box;
  uint32_t left = 0, right = 0;
  uint32_t first = 0, count = 0;
};

/// A binary tree over triangle indices; nodes[root] is the root. Empty when the scene has no
/// valid triangles.
struct BuildTree {
  std::vector<BuildNode> nodes;
  std::vector<uint32_t> prims;
  uint32_t root = 0;
  /// Recorded builds only: the builder's event id of each node (build_trace.h), when it
  /// differs from the node's index (bottom-up and insertion renumber their final tree).
  std::vector<uint32_t> event_ids;
  uint32_t event_id(uint32_t node) const { return event_ids.empty() ? node : event_ids[node]; }
  bool empty() const { return nodes.empty(); }
};

/// The binary nodes below each node of `tree`, itself included (bvh_builders.cpp).
std::vector<uint32_t> binary_subtree_sizes(const BuildTree& tree);

/// Depth bound of every builder's output (the traversal stacks are sized from it).
inline constexpr int kMaxBvhDepth = 96;

/// A hierarchy's memory is linear in its references (the triangles; sbvh: up to
/// sbvh_budget times as many), so it is estimated before the build rather than tracked:
/// an error naming `structure`, the builder and the parameter to lower when the builder's
/// tree, the layout's nodes (`layout_bytes_per_node` each, two nodes per reference) and the
/// builders' scratch would not fit `memory_limit`.
Status check_bvh_memory(const std::string& structure, const Scene& scene, const BvhBuildOptions& options,
                        size_t layout_bytes_per_node, size_t memory_limit);

/// Runs the chosen builder over scene.valid_prims(). Guarantees: every valid triangle is in
/// exactly one leaf (sbvh: in at least one leaf, never twice in the same leaf, and every point
/// of it lies in the box of a leaf that holds it and of that leaf's ancestors -- a spatial
/// split puts a triangle in both children with boxes clipped to their sides, so prims may
/// hold it several times and a box may be smaller than its triangles' boxes), leaves hold
/// at most `leaf_size` triangles, each box bounds its subtree, the triangles below a node
/// are contiguous in prims, and the depth stays below kMaxBvhDepth.
/// `progress` (optional) receives the fraction of triangles placed in leaves so far; it is
/// called from one thread at a time. When its advance() returns false (cancelled), the
/// builder returns as soon as it can with an incomplete tree, which the caller discards.
/// With a `recorder`, every construction step is recorded (build_trace.h): the builder runs
/// instantiated for BuildRecorder, serially, and builds the same tree.
BuildTree build_bvh_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress = nullptr,
                         BuildRecorder* recorder = nullptr);

}  // namespace accel
