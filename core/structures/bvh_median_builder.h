#pragma once
// Median split BVH builder (builder=median): the lecture's first top-down construction.
#include "structures/bvh_build_types.h"

namespace accel {

/// Builds by median splits over scene.valid_prims() with the guarantees of build_bvh_tree():
/// each node sorts its triangles by centre along the axis of `options.axis` (x, x/y/z by
/// depth, or the longest extent of the centres) and gives each child half of them. Nodes
/// are numbered in pre-order, identically for any thread count.
BuildTree build_median_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress = nullptr,
                            BuildRecorder* recorder = nullptr);

}  // namespace accel
