// BVH builders. Index:
//   [SECTION] Names
//   [SECTION] Shared top-down framework (leaf rule, fallback split)
//   [SECTION] Median split
//   [SECTION] SAH sweep (all three axes) and PCA sweep
//   [SECTION] Binned SAH: see bvh_binned_builder.cpp
//   [SECTION] Bottom-up: locally-ordered clustering
//   [SECTION] Insertion (Goldsmith-Salmon)
//   [SECTION] Collapse, depth limit and final layout for the bottom-up builders
#include "structures/bvh_builders.h"

#include "structures/bvh_binned_builder.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>

#include "check.h"
#include "random.h"

namespace accel {

// ============================================================================
// [SECTION] Names
// ============================================================================

const char* builder_name(BvhBuilderKind kind) {
  switch (kind) {
    case BvhBuilderKind::Median: return "median";
    case BvhBuilderKind::Sah: return "sah";
    case BvhBuilderKind::BinnedSah: return "binned_sah";
    case BvhBuilderKind::PcaSah: return "pca_sah";
    case BvhBuilderKind::BottomUp: return "bottom_up";
    case BvhBuilderKind::Insertion: return "insertion";
  }
  return "?";
}

namespace {

// ============================================================================
// [SECTION] Shared top-down framework
// ============================================================================

/// A triangle as the builders see it: its box, the box centre, its index.
struct PrimRef {
  Aabb box;
  Vec3 centroid;
  uint32_t prim;
};

/// A proposed split of refs[begin, end): refs are already partitioned so that
/// [begin, mid) go left. cost is the SAH cost of splitting (NaN for non-SAH splitters).
struct Split {
  bool valid = false;
  size_t mid = 0;
  float cost = 0.0f;
};

/// SAH cost of a split with child areas/counts, relative to the parent's area.
float sah_split_cost(const BvhBuildOptions& o, float parent_area, float left_area, size_t n_left, float right_area,
                     size_t n_right) {
  const float inv = parent_area > 0.0f ? 1.0f / parent_area : 1.0f;
  return o.ct + (left_area * o.leaf_cost(n_left) + right_area * o.leaf_cost(n_right)) * inv;
}

Aabb bounds_of(const std::vector<PrimRef>& refs, size_t begin, size_t end) {
  Aabb b;
  for (size_t i = begin; i < end; ++i) b.extend(refs[i].box);
  return b;
}

Aabb centroid_bounds_of(const std::vector<PrimRef>& refs, size_t begin, size_t end) {
  Aabb b;
  for (size_t i = begin; i < end; ++i) b.extend(refs[i].centroid);
  return b;
}

/// Splits at the object median along the longest centroid axis. Always valid for >= 2
/// refs, even when all centres coincide (then the order is simply halved), so every builder
/// terminates with a depth of O(log n) in the worst case.
Split object_median_split(std::vector<PrimRef>& refs, size_t begin, size_t end, int axis) {
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(refs.begin() + long(begin), refs.begin() + long(mid), refs.begin() + long(end),
                   [axis](const PrimRef& a, const PrimRef& b) {
                     return a.centroid[axis] < b.centroid[axis] ||
                            (a.centroid[axis] == b.centroid[axis] && a.prim < b.prim);
                   });
  return {true, mid, std::nanf("")};
}

/// Top-down recursion shared by the median, SAH and PCA builders (the binned SAH builder has
/// its own, faster recursion in bvh_binned_builder.cpp).
class TopDownBuilder {
 public:
  TopDownBuilder(const BvhBuildOptions& o, std::vector<PrimRef>& refs, BuildTree& out) : o_(o), refs_(refs), out_(out) {}

  uint32_t build(size_t begin, size_t end, int depth) {
    const uint32_t index = uint32_t(out_.nodes.size());
    out_.nodes.emplace_back();
    const Aabb box = bounds_of(refs_, begin, end);
    out_.nodes[index].box = box;
    const size_t count = end - begin;
    Split split;
    if (count > 1) split = choose_split(begin, end, depth, box);
    const bool sah = o_.builder != BvhBuilderKind::Median;
    const float leaf_cost = o_.leaf_cost(count);
    const bool small = count <= size_t(o_.leaf_size);
    if (count <= 1 || (small && (!sah || !split.valid || split.cost >= leaf_cost)) || depth >= kMaxBvhDepth - 1) {
      ACCEL_CHECK(count <= size_t(o_.leaf_size) || depth >= kMaxBvhDepth - 1);
      out_.nodes[index].first = uint32_t(begin);
      out_.nodes[index].count = uint32_t(count);
      return index;
    }
    if (!split.valid || split.mid <= begin || split.mid >= end)
      split = object_median_split(refs_, begin, end, centroid_bounds_of(refs_, begin, end).longest_axis());
    const uint32_t left = build(begin, split.mid, depth + 1);
    const uint32_t right = build(split.mid, end, depth + 1);
    out_.nodes[index].left = left;
    out_.nodes[index].right = right;
    return index;
  }

 private:
  Split choose_split(size_t begin, size_t end, int depth, const Aabb& box) {
    switch (o_.builder) {
      case BvhBuilderKind::Median: return median_split(begin, end, depth);
      case BvhBuilderKind::PcaSah: return pca_split(begin, end, box);
      default: return sweep_split(begin, end, box);
    }
  }

  // --------------------------------------------------------------------------
  // [SECTION] Median split
  // --------------------------------------------------------------------------
  Split median_split(size_t begin, size_t end, int depth) {
    int axis = 0;
    if (o_.axis == MedianAxis::RoundRobin) axis = depth % 3;
    if (o_.axis == MedianAxis::Longest) axis = centroid_bounds_of(refs_, begin, end).longest_axis();
    return object_median_split(refs_, begin, end, axis);
  }

  // --------------------------------------------------------------------------
  // [SECTION] SAH sweep (all three axes) and PCA sweep
  // --------------------------------------------------------------------------

  /// Sweeps the refs in the given order: the best split position and its cost.
  Split sweep_order(const std::vector<uint32_t>& order, size_t begin, float parent_area) {
    const size_t n = order.size();
    right_area_.resize(n);
    Aabb acc;
    for (size_t i = n; i-- > 1;) {
      acc.extend(refs_[begin + order[i]].box);
      right_area_[i] = acc.area();
    }
    Split best;
    acc = Aabb{};
    for (size_t i = 1; i < n; ++i) {
      acc.extend(refs_[begin + order[i - 1]].box);
      const float cost = sah_split_cost(o_, parent_area, acc.area(), i, right_area_[i], n - i);
      if (!best.valid || cost < best.cost) best = {true, begin + i, cost};
    }
    return best;
  }

  /// Applies a sweep order to refs[begin, end).
  void apply_order(const std::vector<uint32_t>& order, size_t begin) {
    scratch_.resize(order.size());
    for (size_t i = 0; i < order.size(); ++i) scratch_[i] = refs_[begin + order[i]];
    std::copy(scratch_.begin(), scratch_.end(), refs_.begin() + long(begin));
  }

  /// Lecture: "try all 3 axes, search for the minimum along each axis, choose the smallest".
  Split sweep_split(size_t begin, size_t end, const Aabb& box) {
    const size_t n = end - begin;
    Split best;
    std::vector<uint32_t> order(n), best_order;
    for (int axis = 0; axis < 3; ++axis) {
      std::iota(order.begin(), order.end(), 0u);
      std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const PrimRef &ra = refs_[begin + a], &rb = refs_[begin + b];
        return ra.centroid[axis] < rb.centroid[axis] || (ra.centroid[axis] == rb.centroid[axis] && ra.prim < rb.prim);
      });
      const Split s = sweep_order(order, begin, box.area());
      if (s.valid && (!best.valid || s.cost < best.cost)) {
        best = s;
        best_order = order;
      }
    }
    if (best.valid) apply_order(best_order, begin);
    return best;
  }

  /// Lecture: "represent polygons by their midpoints, calculate the axis of largest extent
  /// using PCA, project the midpoints onto it and sort, search the minimum of C(B) by sweep".
  Split pca_split(size_t begin, size_t end, const Aabb& box) {
    const size_t n = end - begin;
    DVec3 mean(0.0);
    for (size_t i = begin; i < end; ++i) mean += DVec3(refs_[i].centroid);
    mean /= double(n);
    glm::dmat3 cov(0.0);
    for (size_t i = begin; i < end; ++i) {
      const DVec3 d = DVec3(refs_[i].centroid) - mean;
      cov += glm::outerProduct(d, d);
    }
    // Dominant eigenvector by power iteration, started on the longest centroid axis.
    DVec3 axis(0.0);
    axis[centroid_bounds_of(refs_, begin, end).longest_axis()] = 1.0;
    for (int it = 0; it < 32; ++it) {
      const DVec3 next = cov * axis;
      const double len = glm::length(next);
      if (!(len > 0.0)) break;  // all centres equal: any axis will do
      axis = next / len;
    }
    std::vector<uint32_t> order(n);
    std::vector<double> key(n);
    for (size_t i = 0; i < n; ++i) key[i] = glm::dot(DVec3(refs_[begin + i].centroid), axis);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return key[a] < key[b] || (key[a] == key[b] && refs_[begin + a].prim < refs_[begin + b].prim);
    });
    const Split s = sweep_order(order, begin, box.area());
    if (s.valid) apply_order(order, begin);
    return s;
  }

  const BvhBuildOptions& o_;
  std::vector<PrimRef>& refs_;
  BuildTree& out_;
  std::vector<float> right_area_;
  std::vector<PrimRef> scratch_;
};

std::vector<PrimRef> make_refs(const Scene& scene) {
  std::vector<PrimRef> refs;
  refs.reserve(scene.valid_prims().size());
  for (uint32_t p : scene.valid_prims()) refs.push_back({scene.triangle_bounds(p), scene.centroid(p), p});
  return refs;
}

BuildTree build_top_down(const Scene& scene, const BvhBuildOptions& o) {
  BuildTree tree;
  std::vector<PrimRef> refs = make_refs(scene);
  if (refs.empty()) return tree;
  tree.nodes.reserve(2 * refs.size());
  TopDownBuilder builder(o, refs, tree);
  tree.root = builder.build(0, refs.size(), 0);
  tree.prims.resize(refs.size());
  for (size_t i = 0; i < refs.size(); ++i) tree.prims[i] = refs[i].prim;
  return tree;
}

// ============================================================================
// [SECTION] Collapse, depth limit and final layout for the bottom-up builders
// ============================================================================

/// A binary tree whose leaves hold exactly one triangle, as produced by clustering or insertion.
struct BinaryNode {
  Aabb box;
  uint32_t left = 0, right = 0;
  int64_t prim = -1;  ///< >= 0 for a single-triangle leaf
};

/// Subtree heights (leaf = 0), computed without recursion (trees may be chains).
std::vector<uint32_t> subtree_heights(const std::vector<BinaryNode>& nodes, uint32_t root) {
  std::vector<uint32_t> height(nodes.size(), 0);
  std::vector<std::pair<uint32_t, bool>> stack{{root, false}};
  while (!stack.empty()) {
    auto [i, expanded] = stack.back();
    stack.pop_back();
    if (nodes[i].prim >= 0) continue;
    if (!expanded) {
      stack.push_back({i, true});
      stack.push_back({nodes[i].left, false});
      stack.push_back({nodes[i].right, false});
    } else {
      height[i] = 1 + std::max(height[nodes[i].left], height[nodes[i].right]);
    }
  }
  return height;
}

/// Triangles below node i, in tree order.
void gather_prims(const std::vector<BinaryNode>& nodes, uint32_t i, std::vector<uint32_t>& out) {
  std::vector<uint32_t> stack{i};
  while (!stack.empty()) {
    const uint32_t k = stack.back();
    stack.pop_back();
    if (nodes[k].prim >= 0) {
      out.push_back(uint32_t(nodes[k].prim));
    } else {
      stack.push_back(nodes[k].right);
      stack.push_back(nodes[k].left);
    }
  }
}

/// Balanced median-split subtree over prims[begin, end) (height ~ log2 n); returns its root.
uint32_t build_median_binary(const Scene& scene, std::vector<BinaryNode>& nodes, std::vector<uint32_t>& prims,
                             size_t begin, size_t end) {
  if (end - begin == 1) {
    nodes.push_back({scene.triangle_bounds(prims[begin]), 0, 0, int64_t(prims[begin])});
    return uint32_t(nodes.size() - 1);
  }
  Aabb cb;
  for (size_t i = begin; i < end; ++i) cb.extend(scene.centroid(prims[i]));
  const int axis = cb.longest_axis();
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(prims.begin() + long(begin), prims.begin() + long(mid), prims.begin() + long(end),
                   [&](uint32_t a, uint32_t b) {
                     const float ca = scene.centroid(a)[axis], cb_ = scene.centroid(b)[axis];
                     return ca < cb_ || (ca == cb_ && a < b);
                   });
  const uint32_t l = build_median_binary(scene, nodes, prims, begin, mid);
  const uint32_t r = build_median_binary(scene, nodes, prims, mid, end);
  nodes.push_back({merge(nodes[l].box, nodes[r].box), l, r, -1});
  return uint32_t(nodes.size() - 1);
}

/// Bounds the depth: an adversarial order (e.g. identical triangles) can make insertion
/// grow a chain. Every subtree hanging at depth kCut that is taller than kCut is rebuilt by
/// median split, so no leaf is deeper than about kCut + log2(n) + 1.
void limit_depth(const Scene& scene, std::vector<BinaryNode>& nodes, uint32_t root) {
  constexpr uint32_t kCut = 32;
  static_assert(2 * kCut + 2 < uint32_t(kMaxBvhDepth));
  const std::vector<uint32_t> height = subtree_heights(nodes, root);
  if (height[root] <= 2 * kCut) return;
  std::vector<std::pair<uint32_t, uint32_t>> stack{{root, 0}};  // (node, depth)
  std::vector<uint32_t> prims;
  while (!stack.empty()) {
    auto [i, depth] = stack.back();
    stack.pop_back();
    if (nodes[i].prim >= 0) continue;
    for (int side = 0; side < 2; ++side) {
      const uint32_t child = side == 0 ? nodes[i].left : nodes[i].right;
      if (depth + 1 == kCut && height[child] > kCut) {
        prims.clear();
        gather_prims(nodes, child, prims);
        // build_median_binary appends to `nodes`: take no references across it.
        const uint32_t rebuilt = build_median_binary(scene, nodes, prims, 0, prims.size());
        (side == 0 ? nodes[i].left : nodes[i].right) = rebuilt;
      } else if (depth + 1 < kCut) {
        stack.push_back({child, depth + 1});
      }
    }
  }
}

/// Turns a single-triangle-leaf binary tree into a BuildTree: subtrees of at most
/// leaf_size triangles become one leaf when that is no more expensive by the SAH
/// (ci*n*A <= the subtree's cost), after bounding the depth.
BuildTree finalize_binary_tree(const Scene& scene, std::vector<BinaryNode>& nodes, uint32_t root,
                               const BvhBuildOptions& o) {
  limit_depth(scene, nodes, root);
  const size_t n = nodes.size();
  std::vector<uint32_t> count(n, 0);
  std::vector<float> cost(n, 0.0f);
  std::vector<uint8_t> collapse(n, 0);
  std::vector<std::pair<uint32_t, bool>> stack{{root, false}};
  while (!stack.empty()) {  // post-order: SAH cost of every subtree, bottom up
    auto [i, expanded] = stack.back();
    stack.pop_back();
    const BinaryNode& nd = nodes[i];
    if (nd.prim >= 0) {
      count[i] = 1;
      cost[i] = o.leaf_cost(1) * nd.box.area();
      collapse[i] = 1;
    } else if (!expanded) {
      stack.push_back({i, true});
      stack.push_back({nd.left, false});
      stack.push_back({nd.right, false});
    } else {
      count[i] = count[nd.left] + count[nd.right];
      const float split_cost = o.ct * nd.box.area() + cost[nd.left] + cost[nd.right];
      const float leaf_cost = o.leaf_cost(count[i]) * nd.box.area();
      collapse[i] = count[i] <= uint32_t(o.leaf_size) && leaf_cost <= split_cost;
      cost[i] = collapse[i] ? leaf_cost : split_cost;
    }
  }
  BuildTree tree;
  tree.nodes.reserve(n);
  tree.prims.reserve(count[root]);
  struct Item {
    uint32_t src, dst;
  };
  tree.nodes.emplace_back();
  std::vector<Item> work{{root, 0}};
  std::vector<uint32_t> leaf_prims;
  while (!work.empty()) {
    const Item it = work.back();
    work.pop_back();
    const BinaryNode& nd = nodes[it.src];
    tree.nodes[it.dst].box = nd.box;
    if (collapse[it.src]) {
      leaf_prims.clear();
      gather_prims(nodes, it.src, leaf_prims);
      tree.nodes[it.dst].first = uint32_t(tree.prims.size());
      tree.nodes[it.dst].count = uint32_t(leaf_prims.size());
      tree.prims.insert(tree.prims.end(), leaf_prims.begin(), leaf_prims.end());
      continue;
    }
    const uint32_t l = uint32_t(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.nodes.emplace_back();
    tree.nodes[it.dst].left = l;
    tree.nodes[it.dst].right = l + 1;
    work.push_back({nd.right, l + 1});
    work.push_back({nd.left, l});
  }
  tree.root = 0;
  return tree;
}

// ============================================================================
// [SECTION] Bottom-up: locally-ordered clustering (PLOC, Meister & Bittner 2018)
// ============================================================================

/// Expands 10 bits to 30 by inserting two zeros between bits (Morton code helper).
uint32_t expand_bits(uint32_t v) {
  v = (v * 0x00010001u) & 0xFF0000FFu;
  v = (v * 0x00000101u) & 0x0F00F00Fu;
  v = (v * 0x00000011u) & 0xC30C30C3u;
  v = (v * 0x00000005u) & 0x49249249u;
  return v;
}

BuildTree build_bottom_up(const Scene& scene, const BvhBuildOptions& o) {
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
    nodes.push_back({scene.triangle_bounds(keyed[i].second), 0, 0, int64_t(keyed[i].second)});
  }
  constexpr int kRadius = 16;  // search window on each side (the paper uses 8..32)
  std::vector<uint32_t> nearest;
  std::vector<uint32_t> next;
  while (clusters.size() > 1) {
    const size_t n = clusters.size();
    nearest.assign(n, 0);
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
      float best = kInf;
      uint32_t best_j = uint32_t(i == 0 ? 1 : i - 1);
      const size_t lo = i >= size_t(kRadius) ? i - kRadius : 0, hi = std::min(n, i + kRadius + 1);
      for (size_t j = lo; j < hi; ++j) {
        if (j == i) continue;
        const float a = merge(nodes[clusters[i]].box, nodes[clusters[j]].box).area();
        if (a < best || (a == best && j < best_j)) { best = a; best_j = uint32_t(j); }
      }
      nearest[i] = best_j;
    });
    // Merge mutual nearest neighbours; keep the merged cluster at the lower position so the
    // list stays in Morton order.
    next.clear();
    bool merged_any = false;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t j = nearest[i];
      if (nearest[j] == i) {
        if (i < j) {
          const uint32_t a = clusters[i], b = clusters[j];
          nodes.push_back({merge(nodes[a].box, nodes[b].box), a, b, -1});
          next.push_back(uint32_t(nodes.size() - 1));
          merged_any = true;
        }
        continue;  // j > i was merged into i
      }
      next.push_back(clusters[i]);
    }
    if (!merged_any) {  // cannot happen (the globally closest pair is mutual), but never loop forever
      const uint32_t a = next[0], b = next[1];
      nodes.push_back({merge(nodes[a].box, nodes[b].box), a, b, -1});
      next.erase(next.begin(), next.begin() + 2);
      next.insert(next.begin(), uint32_t(nodes.size() - 1));
    }
    clusters.swap(next);
  }
  return finalize_binary_tree(scene, nodes, clusters[0], o);
}

// ============================================================================
// [SECTION] Insertion (Goldsmith & Salmon 1987)
// ============================================================================

BuildTree build_insertion(const Scene& scene, const BvhBuildOptions& o) {
  std::vector<uint32_t> order = scene.valid_prims();
  if (order.empty()) return {};
  // Goldsmith & Salmon recommend a random insertion order: file order is spatially coherent
  // and grows lopsided trees. A seeded shuffle keeps the build deterministic.
  Rng rng(0x5eed);
  for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.next_u64() % i]);

  std::vector<BinaryNode> nodes;
  std::vector<uint32_t> parent;
  nodes.reserve(2 * order.size());
  parent.reserve(2 * order.size());
  constexpr uint32_t kNone = ~0u;
  uint32_t root = kNone;
  for (uint32_t prim : order) {
    const Aabb box = scene.triangle_bounds(prim);
    const uint32_t leaf = uint32_t(nodes.size());
    nodes.push_back({box, 0, 0, int64_t(prim)});
    parent.push_back(kNone);
    if (root == kNone) {
      root = leaf;
      continue;
    }
    // Sift down: at each node, either make the new triangle its sibling (cost: the area of
    // the new parent) or descend into the child whose area grows least. Every ancestor's
    // area grows too (the inherited cost), which is what makes this the SAH-greedy choice.
    uint32_t at = root;
    float inherited = 0.0f;
    while (nodes[at].prim < 0) {
      const float combined = merge(nodes[at].box, box).area();
      const float here = combined + inherited;
      const float grow = inherited + combined - nodes[at].box.area();
      auto child_cost = [&](uint32_t c) {
        const float a = merge(nodes[c].box, box).area();
        return nodes[c].prim >= 0 ? a + grow : a - nodes[c].box.area() + grow;
      };
      const float cl = child_cost(nodes[at].left), cr = child_cost(nodes[at].right);
      if (here <= cl && here <= cr) break;
      inherited = grow;
      at = cl <= cr ? nodes[at].left : nodes[at].right;
    }
    // New inner node replaces `at`, with children `at` and the new leaf.
    const uint32_t inner = uint32_t(nodes.size());
    nodes.push_back({merge(nodes[at].box, box), at, leaf, -1});
    parent.push_back(parent[at]);
    const uint32_t old_parent = parent[at];
    parent[at] = inner;
    parent[leaf] = inner;
    if (old_parent == kNone) {
      root = inner;
    } else {
      if (nodes[old_parent].left == at) nodes[old_parent].left = inner;
      else nodes[old_parent].right = inner;
      for (uint32_t p = old_parent; p != kNone; p = parent[p]) nodes[p].box.extend(box);  // refit
    }
  }
  return finalize_binary_tree(scene, nodes, root, o);
}

}  // namespace

BuildTree build_bvh_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress) {
  switch (options.builder) {
    case BvhBuilderKind::BinnedSah: return build_binned_sah_tree(scene, options, progress);
    case BvhBuilderKind::BottomUp: return build_bottom_up(scene, options);
    case BvhBuilderKind::Insertion: return build_insertion(scene, options);
    default: return build_top_down(scene, options);
  }
}

}  // namespace accel
