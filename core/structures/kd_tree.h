#pragma once
// kd-tree (lecture "kD-Tree"): split the node's region by one axis-aligned plane, put each
// triangle into the child(ren) it overlaps, recurse. The traversal is the lecture's
// near/far recursion with its three cases, written iteratively with a fixed stack of the
// pending far children (Havran 2000, "Heuristic Ray Shooting Algorithms", TA_B^rec is the
// recursive form; pbrt-v4's KdTreeAggregate is the same loop).
//
// Design decisions (the issue leaves them open):
//  * Node regions are IMPLICIT: the root region is the bounding box of the non-degenerate
//    triangles, a child's region is its parent's cut at the split plane. Nothing but the
//    split position is stored (8-byte nodes, pbrt-v4 layout); the viewer's boxes are
//    rebuilt by descending from the root.
//  * split=sah is Wald & Havran 2006, "On building fast kd-Trees for Ray Tracing, and on
//    doing that in O(N log N)": one sorted event list per axis, swept once per node, kept
//    sorted through the split by filtering plus merging the (sorted) events of the
//    re-clipped straddlers, so no sort per node: O(N log N) overall. It tries all three
//    axes and ignores `axis`, as the lecture says ("try all 3 axes, choose the smallest
//    minimum"). Triangles lying in the split plane go to the side of lower cost. A plane on
//    the region's boundary is a candidate only to cut the triangles lying in it off into a
//    flat cell (their sec. 4.4; walls of axis-aligned rooms). It stops (leaf) when no plane
//    costs less than the leaf, ci * N.
//  * split=middle / median: the region's middle, or the median of the triangles' clipped box
//    centres, along the axis chosen by `axis`. They stop at leaf_size / max_depth, and two
//    guards stop the explosion of references a kd-tree risks (kd_tree.cpp, build_node()):
//    a split sending every triangle to both sides makes a leaf, and so does the third split
//    on a path whose SAH cost is not below the leaf's (pbrt's badRefines), e.g. around a
//    vertex shared by more than leaf_size triangles, which no plane ever separates.
//  * clip=on ("perfect splits", Havran 2000, Wald & Havran 2006 sec. 4.3): a triangle's
//    extent in a node is the box of the triangle clipped to the node's region, so split
//    candidates and the straddle test see only the part inside, and a triangle whose box
//    overlaps a child but which itself misses the child is not stored there. The clipping
//    is conservative (see kd_tree.cpp): it may keep a triangle that only grazes a child,
//    never drop one that touches it.
//  * Triangles touching the split plane from one side, and triangles in the plane, are
//    stored on one side only. This is correct because the traversal visits BOTH closed
//    children whenever the ray meets the plane inside the node's interval, and visits both
//    (with the whole interval) when the ray lies in the plane (zero direction component,
//    origin on the plane: t_split = 0 * inf = NaN).
//  * Robustness: the split distance t_split = (split - o) * (1/d) carries at most 3
//    roundings, so cases (b) and (c) are taken only when t_split lies beyond t_max / before
//    t_min by more than that (kd_lower()/kd_upper(), relative 2*gamma(3)); otherwise both
//    children are visited. A far child is skipped for the closest hit only when the hit is
//    before the lowest value its entry distance could have. So rounding can add a node
//    visit, never lose a triangle.
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "structure.h"

namespace accel {

/// Deepest leaf a kd-tree can have (root = depth 0): the upper end of max_depth, and the
/// size of the traversal's stack (one pending far child per level at most).
inline constexpr int kKdMaxDepth = 64;

/// One kd-tree node, 8 bytes (pbrt-v4 KdTreeAggregate's KdTreeNode). The first (below)
/// child of an inner node is the next node in the array; only the second is stored.
struct KdNode {
  /// Inner node: the split position (float bits). Leaf: offset of its first triangle in
  /// KdTreeData::prim_ids.
  uint32_t payload = 0;
  /// Low 2 bits: split axis 0/1/2 of an inner node, or 3 for a leaf. Upper 30 bits: inner
  /// node = index of its above child (coordinates >= split); leaf = number of triangles.
  uint32_t bits = 3;

  bool leaf() const { return (bits & 3u) == 3u; }
  int axis() const { return int(bits & 3u); }
  float split() const { return std::bit_cast<float>(payload); }
  NodeId above_child() const { return bits >> 2; }
  uint32_t prim_count() const { return bits >> 2; }
  uint32_t prim_offset() const { return payload; }

  static KdNode make_inner(int axis, float split, NodeId above) {
    return KdNode{std::bit_cast<uint32_t>(split), (above << 2) | uint32_t(axis)};
  }
  static KdNode make_leaf(uint32_t offset, uint32_t count) { return KdNode{offset, (count << 2) | 3u}; }
};
static_assert(sizeof(KdNode) == 8, "kd-tree nodes are two 32-bit words");

/// Largest index / count the 30 upper bits of KdNode::bits hold.
inline constexpr uint32_t kKdMaxIndex = (1u << 30) - 1;

/// Where a node is split.
enum class KdSplit : uint8_t {
  Middle,  ///< middle of the node's region along the chosen axis
  Median,  ///< median of the triangles' (clipped) box centres along the chosen axis
  Sah,     ///< minimum of the surface area heuristic over all three axes (Wald & Havran 2006)
};

/// Which axis middle and median split (sah tries all three).
enum class KdAxis : uint8_t {
  RoundRobin,  ///< x, y, z, x, ... by depth (skipping an axis along which the region is flat)
  Longest,     ///< longest axis of the node's REGION (not of its triangles' box)
};

/// Build settings: the structure's parameters, validated, plus the memory budget.
///
/// Default SAH constants ct = 1, ci = 1, empty_bonus = 0.2, leaf_size = 1, clip on: measured
/// single-threaded (CPU time, 77k primary + random rays) on bunny, dragon, sibenik and
/// crytek_sponza, ci = 1 was fastest or within noise of it on every scene (ci = 1.5: 0-5%
/// slower and 40% more memory; ci = 3: 5-13% slower; pbrt's isect 80 / emptyBonus 0.5: 10-25%
/// slower, as the empty-space cuts it favours use up the depth limit and leave big leaves).
/// A node step costs about as much as a watertight triangle test here because it is
/// memory bound (the node load is the hottest instruction of the loop), so ci/ct ~ 1, near
/// Wald & Havran's K_I/K_T = 20/15. Their lambda = 0.8 (empty_bonus 0.2) sat between 0.1 and
/// 0.3, which were within noise; clip on was 5-20% faster than off; leaf_size 2 made no
/// difference, 1 leaves the decision to the SAH.
struct KdBuildOptions {
  KdSplit split = KdSplit::Sah;
  KdAxis axis = KdAxis::Longest;
  int max_depth = 0;            ///< deepest leaf; 0 = auto, round(8 + 1.3 log2 N)
  int leaf_size = 1;            ///< a node with <= leaf_size triangles is a leaf
  double ct = 1.0;              ///< SAH cost of one traversal step
  double ci = 1.0;              ///< SAH cost of one ray/triangle test
  double empty_bonus = 0.2;     ///< SAH cost factor (1 - empty_bonus) when one child is empty
  bool clip = true;             ///< perfect splits: clip triangles to the node's region
  size_t node_limit = size_t(1) << 26;       ///< build fails beyond this many nodes (512 MiB)
  size_t reference_limit = size_t(1) << 27;  ///< ... or this many triangle references (512 MiB)
  size_t event_limit = size_t(1) << 27;      ///< ... or this many live build events (1 GiB)
};

/// The automatic depth limit for `n` triangles: round(8 + 1.3 log2 n), at most kKdMaxDepth
/// (pbrt's KdTreeAggregate, after Havran 2000).
int kd_auto_max_depth(size_t n);

/// How many leaves stopped for which reason (stats and tests).
struct KdLeafReasons {
  size_t few_prims = 0;    ///< at most leaf_size triangles
  size_t max_depth = 0;    ///< reached the depth limit
  size_t no_gain = 0;      ///< sah: no plane costs less than the leaf (Wald & Havran's termination)
  size_t no_progress = 0;  ///< the split sent every triangle to both sides
  size_t bad_refines = 0;  ///< middle/median: third split on the path that did not pay by SAH
  size_t thin = 0;         ///< middle/median: region too thin to put a plane inside
};

/// A built kd-tree: plain data.
struct KdTreeData {
  Aabb root_box;                   ///< region of node 0: box of the non-degenerate triangles
  std::vector<KdNode> nodes;       ///< nodes[0] is the root; always at least one node
  std::vector<uint32_t> prim_ids;  ///< triangle ids of all leaves, leaf by leaf
  int max_depth_limit = 0;         ///< the depth limit used (max_depth resolved)
  int depth = 0;                   ///< deepest leaf
  KdLeafReasons leaf_reasons;
};

/// Builds a kd-tree over `scene.valid_prims()`. Errors (naming the parameters to change)
/// when the node, reference or event budget of `options` would be exceeded.
Result<KdTreeData> build_kd_tree(const Scene& scene, const KdBuildOptions& options);

/// Region of the below (`above` false: coordinates <= split) or above child of a node
/// whose region is `box`, split at `split` along `axis`.
inline Aabb kd_child_box(const Aabb& box, int axis, float split, bool above) {
  Aabb child = box;
  (above ? child.min : child.max)[axis] = split;
  return child;
}

/// A value certainly <= the exact quantity that `t` approximates with at most 3 roundings
/// (relative error gamma(3); 2*gamma(3) leaves room for rounding this product). NaN stays NaN.
inline float kd_lower(float t) { return t * (t > 0.0f ? 1.0f - 2.0f * gamma_bound(3) : 1.0f + 2.0f * gamma_bound(3)); }
/// A value certainly >= the exact quantity that `t` approximates (see kd_lower()).
inline float kd_upper(float t) { return t * (t > 0.0f ? 1.0f + 2.0f * gamma_bound(3) : 1.0f - 2.0f * gamma_bound(3)); }

/// kd-tree over the scene's non-degenerate triangles. Parameters: split (middle|median|sah),
/// axis (round_robin|longest), max_depth, leaf_size, ct, ci, empty_bonus, clip (on|off).
class KdTree final : public StructureWithTraversal<KdTree> {
 public:
  /// The one declaration of the kd-tree's parameters (over its build options).
  static const ParamTable<KdBuildOptions>& param_table();
  static std::vector<ParamSpec> param_specs() { return param_table().specs(); }
  std::string name() const override { return "kdtree"; }
  void for_each_node(const std::function<void(const NodeView&)>& fn) const override;
  NodeView node_view(NodeId id) const override;
  std::vector<uint32_t> node_prims(NodeId id) const override;
  /// The built data, for tests.
  const KdTreeData& data() const { return data_; }

  /// The one traversal: the lecture's traverse(r, n, t_min, t_max), iterative.
  ///  * The ray is first clipped to the root region (BoxTester) -> [t_min, t_max].
  ///  * At an inner node, t_split = distance to the plane; "near" (first) is the child the
  ///    ray is in before t_split: below when dir[axis] is +0 or positive, above when -0 or
  ///    negative. For a ray starting before the plane this is the lecture's "child
  ///    containing the origin"; unlike that rule it needs no special case for a plane
  ///    behind the origin (pbrt's t_split <= 0 test) and stays right for tmin < 0.
  ///    (b) t_split > t_max: first only, second culled (MissedBounds);
  ///    (c) t_split < t_min: second only, first culled (MissedBounds);
  ///    (a) otherwise: push second with [t_split, t_max], descend first with [t_min, t_split].
  ///  * At a leaf every triangle is tested against [tmin, closest]: a hit beyond the
  ///    leaf's t_max is kept as a candidate. Then the next far child is popped; it is skipped
  ///    (BeyondClosestHit) when the closest hit lies before its entry distance, i.e. the
  ///    lecture's early exit: its entry distance is the t_max of the near side just done,
  ///    so "closest < t_split" after the near side ends the query. Checking at the pop
  ///    (not "closest <= this leaf's t_max") stays right when the ray lies in a split plane
  ///    and both children share one interval.
  template <class Sink>
  Hit traverse(const Ray& ray, Sink& sink) const;

 protected:
  Status build_impl(const Scene& scene, const ParamSet& params) override;
  BuildStats compute_stats() const override;

 private:
  const Scene* scene_ = nullptr;
  KdTreeData data_;
  KdBuildOptions options_;
};

template <class Sink>
Hit KdTree::traverse(const Ray& ray, Sink& sink) const {
  const TriangleTester tester(ray, kernel_);
  const BoxTester boxes(ray);
  Hit closest = no_hit(ray);
  float t_min = 0.0f, t_max = 0.0f;
  if (!scene_ || data_.prim_ids.empty() || !boxes.intersect(data_.root_box, ray.tmin, ray.tmax, &t_min, &t_max)) {
    sink.cull(0, 0, CullReason::MissedBounds, ray.tmin);
  } else {
    struct Entry {
      NodeId node;
      int depth;
      float t_min, t_max;
    };
    Entry stack[kKdMaxDepth];  // one pending far child per level of the current path
    int top = 0;
    const KdNode* nodes = data_.nodes.data();
    const uint32_t* prim_ids = data_.prim_ids.data();
    NodeId id = 0;
    int depth = 0;
    for (;;) {
      sink.visit(id, depth, t_min, t_max);
      const KdNode node = nodes[id];
      if (!node.leaf()) {
        const int axis = node.axis();
        const float t_split = (node.split() - boxes.org[axis]) * boxes.inv_dir[axis];
        const bool below_first = !std::signbit(ray.dir[axis]);
        const NodeId first = below_first ? id + 1 : node.above_child();
        const NodeId second = below_first ? node.above_child() : id + 1;
        ++depth;
        if (kd_lower(t_split) > kd_upper(t_max)) {  // (b) the plane lies beyond the interval
          sink.cull(second, depth, CullReason::MissedBounds, t_split);
          id = first;
        } else if (kd_upper(t_split) < kd_lower(t_min)) {  // (c) the plane lies before it
          sink.cull(first, depth, CullReason::MissedBounds, t_split);
          id = second;
        } else {  // (a); a NaN t_split (ray in the plane) keeps [t_min, t_max] for both
          const float far_min = t_split > t_min ? t_split : t_min;
          ACCEL_DCHECK(top < kKdMaxDepth);
          stack[top++] = {second, depth, far_min, t_max};
          sink.push(second, depth, far_min);
          if (t_split < t_max) t_max = t_split;
          id = first;
        }
        continue;
      }
      const uint32_t begin = node.prim_offset(), end = begin + node.prim_count();
      for (uint32_t k = begin; k < end; ++k) test_triangle(*scene_, tester, prim_ids[k], closest, sink);
      // Next pending far child, unless the closest hit lies before it (the early exit).
      bool more = false;
      while (top > 0) {
        const Entry& e = stack[--top];
        sink.pop(e.node, e.depth, e.t_min);
        if (closest.t < kd_lower(e.t_min)) {
          sink.cull(e.node, e.depth, CullReason::BeyondClosestHit, e.t_min);
          continue;
        }
        id = e.node;
        depth = e.depth;
        t_min = e.t_min;
        t_max = e.t_max;
        more = true;
        break;
      }
      if (!more) break;
    }
  }
  return finish_query(closest, sink);
}

}  // namespace accel
