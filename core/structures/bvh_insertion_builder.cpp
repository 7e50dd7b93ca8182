// Iterative insertion (lecture, BVH: "start with an empty tree, iteratively add polygons, let
// each polygon sift through the tree"), after Goldsmith & Salmon 1987, "Automatic creation of
// object hierarchies for ray tracing": at each node the triangle either becomes the node's
// sibling or descends into the child whose surface area grows least, counting the growth of
// every ancestor. bvh_binary_tree.h finishes the tree.
#include "structures/bvh_insertion_builder.h"

#include <emmintrin.h>  // _mm_prefetch: SSE, part of every x86-64 CPU (as in geometry.h)

#include <utility>

#include "random.h"
#include "structures/bvh_binary_tree.h"

namespace accel {
namespace {

using namespace bottom_up;

template <class Sink>
BuildTree build_insertion(const Scene& scene, const BvhBuildOptions& o, ProgressSpan* progress, Sink& sink) {
  sink.scene_box(scene.bounds());
  std::vector<uint32_t> order = scene.valid_prims();
  if (order.empty()) return {};
  // Goldsmith & Salmon recommend a random insertion order: file order is spatially coherent
  // and grows lopsided trees. A seeded shuffle keeps the build deterministic.
  Rng rng(0x5eed);
  for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.next_u64() % i]);

  std::vector<BinaryNode> nodes;
  nodes.reserve(2 * order.size());
  constexpr uint32_t kNone = ~0u;
  constexpr size_t kProgressBatch = 1024;  // triangles inserted between progress reports
  uint32_t root = kNone;
  for (size_t inserted = 0; inserted < order.size(); ++inserted) {
    if (progress && inserted % kProgressBatch == 0 && !progress->advance(double(inserted) / double(order.size())))
      return {};
    const uint32_t prim = order[inserted];
    // The shuffled order reads the triangle boxes at random: fetch a few ahead.
    constexpr size_t kAhead = 8;
    if (inserted + kAhead < order.size())
      _mm_prefetch(reinterpret_cast<const char*>(&scene.triangle_bounds(order[inserted + kAhead])), _MM_HINT_T0);
    const Aabb box = scene.triangle_bounds(prim);
    const uint32_t leaf = uint32_t(nodes.size());
    nodes.push_back(BinaryNode::leaf_of(box, prim));
    if constexpr (Sink::kRecords) record_cluster(scene, leaf, box, prim, sink);
    if (root == kNone) {
      root = leaf;
      continue;
    }
    // Sift down: at each node, either make the new triangle its sibling (cost: the area of
    // the new parent) or descend into the child whose area grows least. Every ancestor's
    // area grows too (the inherited cost), which is what makes this the SAH-greedy choice.
    // A node we descend from becomes an ancestor of the new triangle, so its box is
    // refitted right then, while it is in cache (its old box was read already; nothing
    // further down reads it).
    uint32_t at = root, above = kNone;
    float inherited = 0.0f;
    [[maybe_unused]] int depth = 0;  // recorded builds: the depth of `at`
    while (!nodes[at].is_leaf()) {
      const BinaryNode& node = nodes[at];
      const BinaryNode &l = nodes[node.left], &r = nodes[node.right];
      // The next level's nodes load while this one is decided.
      if (!l.is_leaf()) {
        _mm_prefetch(reinterpret_cast<const char*>(&nodes[l.left]), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(&nodes[l.right]), _MM_HINT_T0);
      }
      if (!r.is_leaf()) {
        _mm_prefetch(reinterpret_cast<const char*>(&nodes[r.left]), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(&nodes[r.right]), _MM_HINT_T0);
      }
      const float combined = merge(node.box, box).area();
      const float here = combined + inherited;
      const float grow = inherited + combined - node.box.area();
      auto child_cost = [&](const BinaryNode& c) {
        const float a = merge(c.box, box).area();
        return c.is_leaf() ? a + grow : a - c.box.area() + grow;
      };
      const float cl = child_cost(l), cr = child_cost(r);
      if constexpr (Sink::kRecords) {
        const float costs[3] = {here, cl, cr};
        const int choice = here <= cl && here <= cr ? 0 : cl <= cr ? 1 : 2;
        // The node grows only when the triangle goes on below it; as the sibling here, the
        // triangle is bounded by the new parent instead (the merge step), the node keeps its box.
        sink.insert_step(prim, at, depth, choice == 0 ? node.box : merge(node.box, box), costs, choice);
        ++depth;
      }
      if (here <= cl && here <= cr) break;
      inherited = grow;
      nodes[at].box.extend(box);
      above = at;
      at = cl <= cr ? node.left : node.right;
    }
    // New inner node replaces `at`, with children `at` and the new leaf.
    const uint32_t inner = uint32_t(nodes.size());
    nodes.push_back(BinaryNode::inner(merge(nodes[at].box, box), at, leaf));
    if constexpr (Sink::kRecords) sink.merge(inner, at, leaf, nodes.back().box, nodes.back().box.area());
    if (above == kNone) {
      root = inner;
    } else if (nodes[above].left == at) {
      nodes[above].left = inner;
    } else {
      nodes[above].right = inner;
    }
  }
  return finalize_binary_tree(scene, nodes, root, o, sink);
}

}  // namespace

BuildTree build_insertion_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                               BuildRecorder* recorder) {
  return with_build_sink(recorder, [&](auto& sink) { return build_insertion(scene, options, progress, sink); });
}

}  // namespace accel
