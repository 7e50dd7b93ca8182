#pragma once
// kd-tree (lecture "kD-Tree"): split the node's region by one axis-aligned plane, put each
// triangle into the child(ren) it overlaps, recurse. The traversal is the lecture's
// near/far recursion with its three cases, written iteratively with a fixed stack of the
// pending far children (Havran 2000, "Heuristic Ray Shooting Algorithms", TA_B^rec is the
// recursive form; pbrt-v4's KdTreeAggregate is the same loop).
//
// Design decisions (the issue leaves them open; those of the build are in kd_builder.h):
//  * Node regions are IMPLICIT: the root region is the bounding box of the non-degenerate
//    triangles, a child's region is its parent's cut at the split plane. Nothing but the
//    split position is stored (8-byte nodes, pbrt-v4 layout); the viewer's boxes are
//    rebuilt by descending from the root.
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
#include <cmath>
#include <cstdint>
#include <vector>

#include "structure.h"
#include "structures/kd_node.h"

namespace accel {

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
  std::vector<NodeId> node_children(NodeId id) const override;
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
  template <TraversalSink Sink>
  Hit traverse(const Ray& ray, Sink& sink) const;

 protected:
  Status build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) override;
  BuildStats compute_stats() const override;

 private:
  const Scene* scene_ = nullptr;
  KdTreeData data_;
  KdBuildOptions options_;
};

template <TraversalSink Sink>
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
          if constexpr (Sink::kRecords)
            sink.vars(KdSplitVars{t_min, t_split, t_max, first, second, axis, KdCase::NearOnly});
          sink.cull(second, depth, CullReason::MissedBounds, t_split);
          id = first;
        } else if (kd_upper(t_split) < kd_lower(t_min)) {  // (c) the plane lies before it
          if constexpr (Sink::kRecords)
            sink.vars(KdSplitVars{t_min, t_split, t_max, first, second, axis, KdCase::FarOnly});
          sink.cull(first, depth, CullReason::MissedBounds, t_split);
          id = second;
        } else {  // (a); a NaN t_split (ray in the plane) keeps [t_min, t_max] for both
          if constexpr (Sink::kRecords)
            sink.vars(KdSplitVars{t_min, t_split, t_max, first, second, axis, KdCase::Both});
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
        if constexpr (Sink::kRecords)  // the lecture's "if t_hit < t_split return"
          sink.vars(KdExitVars{closest.t, e.t_min, e.node, closest.t < kd_lower(e.t_min)});
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
