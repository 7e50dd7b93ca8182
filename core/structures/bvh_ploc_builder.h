#pragma once
// Bottom-up BVH builder (builder=bottom_up): locally-ordered agglomerative clustering (PLOC).
#include "structures/bvh_build_types.h"

namespace accel {

/// Builds over scene.valid_prims() with the guarantees of build_bvh_tree(): every triangle
/// starts as a cluster; each round merges the clusters that are each other's nearest
/// neighbour (least merged box area) among their neighbours along a Morton curve, until one
/// is left. The tree is the same for any thread count.
BuildTree build_ploc_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress = nullptr,
                          BuildRecorder* recorder = nullptr);

}  // namespace accel
