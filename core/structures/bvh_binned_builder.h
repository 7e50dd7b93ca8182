#pragma once
// Fast, parallel binned SAH builder (builder=binned_sah), after Wald 2007, "On fast
// construction of SAH-based BVHs": flat primitive references built once, one binning pass
// over all three axes, an in-place partition that also yields the children's bounds, and
// TBB tasks for the upper levels. The tree does not depend on the thread count.
#include "structures/bvh_build_types.h"

namespace accel {

/// Builds the binned SAH tree over scene.valid_prims() with the guarantees of
/// build_bvh_tree(). `options.bins` is the maximum bin count per axis; a node of n
/// references uses min(bins, 4 + n / 4) bins (small nodes need fewer candidate planes).
/// Nodes are numbered in pre-order (left subtree first), identically for any thread count.
/// With a `recorder`, every construction step is recorded (build_trace.h) and the build runs serially.
BuildTree build_binned_sah_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress = nullptr,
                                BuildRecorder* recorder = nullptr);

}  // namespace accel
