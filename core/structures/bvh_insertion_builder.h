#pragma once
// Insertion BVH builder (builder=insertion): Goldsmith & Salmon's incremental construction.
#include "structures/bvh_build_types.h"

namespace accel {

/// Builds over scene.valid_prims() with the guarantees of build_bvh_tree(): the triangles,
/// in a seeded random order, are inserted one by one, each sifting down the tree to where
/// it adds the least surface area. Serial and deterministic.
BuildTree build_insertion_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress = nullptr,
                               BuildRecorder* recorder = nullptr);

}  // namespace accel
