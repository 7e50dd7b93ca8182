// Bottom-up construction (lecture, BVH: "recursively combine objects/BVs and enclose them in
// a larger BV; problem: how to choose the objects to be combined?"): here the answer of
// Meister & Bittner 2018, "Parallel locally-ordered clustering for bounding volume hierarchy
// construction" (PLOC): clusters sorted along a Morton curve, each merged with its nearest
// neighbour within a window when the choice is mutual. bvh_binary_tree.h finishes the tree.
#include "structures/bvh_ploc_builder.h"

#include <algorithm>
#include <array>

#include "parallel.h"
#include "structures/bvh_binary_tree.h"

namespace accel {
namespace {

using namespace bottom_up;

/// Expands 10 bits to 30 by inserting two zeros between bits (Morton code helper).
uint32_t expand_bits(uint32_t v) {
  v = (v * 0x00010001u) & 0xFF0000FFu;
  v = (v * 0x00000101u) & 0x0F00F00Fu;
  v = (v * 0x00000011u) & 0xC30C30C3u;
  v = (v * 0x00000005u) & 0x49249249u;
  return v;
}

/// The nearest neighbour of every cluster within `radius` positions on each side of the
/// list: the one whose merged box has the least area, ties to the lower position (so the
/// answer does not depend on the order the candidates are seen in).
///
/// Each pair is measured once (the merged area is symmetric: merge(a, b) and merge(b, a)
/// differ at most in the sign of a zero, which compares equal) and offered to both ends.
/// Blocks of the list are independent tasks: a block measures its own pairs and those
/// reaching into it from the `radius` positions before it.
void nearest_neighbours(const std::vector<Aabb>& boxes, int radius, std::vector<uint32_t>& nearest) {
  const size_t n = boxes.size(), r = size_t(radius);
  constexpr size_t kBlock = 2048;
  nearest.resize(n);
  par::parallel_for(size_t(0), (n + kBlock - 1) / kBlock, [&](size_t block) {
    const size_t begin = block * kBlock, end = std::min(n, begin + kBlock);
    std::array<float, kBlock> best_area;
    std::array<uint32_t, kBlock> best;
    for (size_t i = begin; i < end; ++i) {
      best_area[i - begin] = kInf;
      best[i - begin] = uint32_t(i == 0 ? 1 : i - 1);
    }
    const auto offer = [&](size_t i, size_t j, float area) {
      float& a = best_area[i - begin];
      uint32_t& b = best[i - begin];
      if (area < a || (area == a && j < b)) {
        a = area;
        b = uint32_t(j);
      }
    };
    for (size_t i = begin >= r ? begin - r : 0; i < end; ++i) {
      const bool i_inside = i >= begin;
      const size_t j_begin = std::max(i + 1, begin);
      const size_t j_end = std::min(i_inside ? n : end, i + r + 1);
      for (size_t j = j_begin; j < j_end; ++j) {
        const float area = merge(boxes[i], boxes[j]).area();
        if (i_inside) offer(i, j, area);
        if (j < end) offer(j, i, area);
      }
    }
    std::copy(best.begin(), best.begin() + long(end - begin), nearest.begin() + long(begin));
  });
}

template <class Sink>
BuildTree build_bottom_up(const Scene& scene, const BvhBuildOptions& o, ProgressSpan* progress, Sink& sink) {
  sink.scene_box(scene.bounds());
  const auto& prims = scene.valid_prims();
  if (prims.empty()) return {};
  std::vector<BinaryNode> nodes;
  nodes.reserve(2 * prims.size());
  Aabb cb;
  for (uint32_t p : prims) cb.extend(scene.centroid(p));
  const Vec3 extent = glm::max(cb.extent(), Vec3(1e-30f));
  // Clusters start as single triangles ordered along a Morton curve, so spatial neighbours
  // are near each other in the list and the nearest-neighbour search can stay local.
  std::vector<std::pair<uint32_t, uint32_t>> keyed(prims.size());
  for (size_t i = 0; i < prims.size(); ++i) {
    const Vec3 q = glm::clamp((scene.centroid(prims[i]) - cb.min) / extent, Vec3(0.0f), Vec3(1.0f)) * 1023.0f;
    keyed[i] = {(expand_bits(uint32_t(q.x)) << 2) | (expand_bits(uint32_t(q.y)) << 1) | expand_bits(uint32_t(q.z)),
                prims[i]};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint32_t> clusters(prims.size());
  for (size_t i = 0; i < keyed.size(); ++i) {
    clusters[i] = uint32_t(nodes.size());
    nodes.push_back(BinaryNode::leaf_of(scene.triangle_bounds(keyed[i].second), keyed[i].second));
    if constexpr (Sink::kRecords) record_cluster(scene, clusters[i], nodes.back().box, keyed[i].second, sink);
  }
  constexpr int kRadius = 16;  // search window on each side (the paper uses 8..32)
  std::vector<Aabb> boxes;
  std::vector<uint32_t> nearest;
  std::vector<uint32_t> next;
  while (clusters.size() > 1) {
    const size_t n = clusters.size();
    boxes.resize(n);
    for (size_t i = 0; i < n; ++i) boxes[i] = nodes[clusters[i]].box;  // read 2 * kRadius times each
    nearest_neighbours(boxes, kRadius, nearest);
    // Merge mutual nearest neighbours; keep the merged cluster at the lower position so the
    // list stays in Morton order.
    next.clear();
    bool merged_any = false;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t j = nearest[i];
      if (nearest[j] == i) {
        if (i < j) {
          const uint32_t a = clusters[i], b = clusters[j];
          nodes.push_back(BinaryNode::inner(merge(nodes[a].box, nodes[b].box), a, b));
          next.push_back(uint32_t(nodes.size() - 1));
          merged_any = true;
          if constexpr (Sink::kRecords) sink.merge(next.back(), a, b, nodes.back().box, nodes.back().box.area());
        }
        continue;  // j > i was merged into i
      }
      next.push_back(clusters[i]);
    }
    if (!merged_any) {  // cannot happen (the globally closest pair is mutual), but never loop forever
      const uint32_t a = next[0], b = next[1];
      nodes.push_back(BinaryNode::inner(merge(nodes[a].box, nodes[b].box), a, b));
      if constexpr (Sink::kRecords)
        sink.merge(uint32_t(nodes.size() - 1), a, b, nodes.back().box, nodes.back().box.area());
      next.erase(next.begin(), next.begin() + 2);
      next.insert(next.begin(), uint32_t(nodes.size() - 1));
    }
    clusters.swap(next);
    // Progress: merges done (n - 1 in all) per round; the rounds shrink geometrically.
    if (progress && !progress->advance(double(prims.size() - clusters.size()) / double(prims.size()))) return {};
  }
  return finalize_binary_tree(scene, nodes, clusters[0], o, sink);
}

}  // namespace

BuildTree build_ploc_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                          BuildRecorder* recorder) {
  return with_build_sink(recorder, [&](auto& sink) { return build_bottom_up(scene, options, progress, sink); });
}

}  // namespace accel
