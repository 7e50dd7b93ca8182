#pragma once
// SAH plane sweep BVH builder (builder=sah): every split position on all three axes.
#include "structures/bvh_build_types.h"

namespace accel {

/// Builds over scene.valid_prims() with the guarantees of build_bvh_tree(): each node tries
/// every split between consecutive centres on x, y and z and takes the one of least SAH
/// cost (a leaf when no split is cheaper). Nodes are numbered in pre-order, identically for
/// any thread count.
BuildTree build_sweep_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress = nullptr,
                           BuildRecorder* recorder = nullptr);

}  // namespace accel
