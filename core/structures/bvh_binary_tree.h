#pragma once
// What the bottom-up builders share (bvh_ploc_builder.cpp, bvh_insertion_builder.cpp): they
// grow a binary tree whose leaves hold one triangle each, then finalize_binary_tree() bounds
// its depth, collapses small subtrees into leaves where the SAH says so, and lays it out as
// a BuildTree. Not a public interface: only those two builders include it.
#include <cstdint>
#include <vector>

#include "build_trace.h"
#include "structures/bvh_build_types.h"

namespace accel::bottom_up {

/// A binary tree whose leaves hold exactly one triangle, as produced by clustering or
/// insertion. 32 bytes, aligned, so a node is one cache line access: insertion walks the
/// tree in random order, and its speed is the number of lines it touches.
struct alignas(32) BinaryNode {
  static constexpr uint32_t kLeaf = ~0u;
  Aabb box;
  uint32_t left = 0;   ///< inner: first child; leaf: kLeaf
  uint32_t right = 0;  ///< inner: second child; leaf: the triangle

  static BinaryNode leaf_of(const Aabb& box, uint32_t prim) { return {box, kLeaf, prim}; }
  static BinaryNode inner(const Aabb& box, uint32_t left, uint32_t right) { return {box, left, right}; }
  bool is_leaf() const { return left == kLeaf; }
  uint32_t prim() const { return right; }
};
static_assert(sizeof(BinaryNode) == 32);

/// Turns a single-triangle-leaf binary tree into a BuildTree: subtrees of at most
/// leaf_size triangles become one leaf when that is no more expensive by the SAH
/// (ci*n*A <= the subtree's cost), after bounding the depth (an adversarial insertion order
/// can grow a chain). Recorded builds: tree.event_ids maps every node to its binary node
/// (the event ids), and each inner node that becomes a leaf is recorded as a leaf step (the
/// replay drops its children). Instantiated for NullBuildSink and BuildRecorder.
template <class Sink>
BuildTree finalize_binary_tree(const Scene& scene, std::vector<BinaryNode>& nodes, uint32_t root,
                               const BvhBuildOptions& o, Sink& sink);

/// Records each triangle entering as a cluster: a parentless node that is a leaf.
template <class Sink>
void record_cluster(const Scene& scene, uint32_t id, const Aabb& box, uint32_t prim, Sink& sink) {
  Aabb centroid;
  centroid.extend(scene.centroid(prim));
  sink.node(id, kNoBuildNode, 0, box, centroid, &prim, 1);
  sink.leaf(id, LeafReason::Cluster, &prim, 1);
}

}  // namespace accel::bottom_up
