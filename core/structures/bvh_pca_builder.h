#pragma once
// PCA sweep BVH builder (builder=pca_sah): the SAH plane sweep along each node's principal axis.
#include "structures/bvh_build_types.h"

namespace accel {

/// Builds over scene.valid_prims() with the guarantees of build_bvh_tree(): each node
/// projects its centres onto their principal axis, sorts them along it and splits where the
/// SAH cost is least. Nodes are numbered in pre-order, identically for any thread count.
BuildTree build_pca_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress = nullptr,
                         BuildRecorder* recorder = nullptr);

}  // namespace accel
