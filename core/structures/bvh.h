#pragma once
// Bounding volume hierarchy with axis-aligned boxes (AABB tree). Builders: bvh_builders.h;
// traversal orders: hierarchy.h. Two layouts of the same built tree: the lecture's binary
// tree (width=2, hierarchy.h) and 4-wide nodes tested with SSE (width=4, wide_bvh.h, the
// default because it is the fastest).
#include "structures/hierarchy.h"
#include "structures/wide_bvh.h"

namespace accel {

class Bvh final : public Hierarchy<Bvh, Aabb, BoxTester> {
 public:
  static std::vector<ParamSpec> param_specs();
  std::string name() const override { return "bvh"; }
  /// Children per inner node of the stored layout: 2 or 4.
  int width() const { return width_; }
  /// The 4-wide layout (empty when width is 2).
  const WideBvh& wide() const { return wide_; }

  /// The one query, in the layout chosen at build time.
  template <class Sink>
  Hit traverse(const Ray& ray, Sink& sink) const {
    if (width_ == 2) return Hierarchy::traverse(ray, sink);
    Hit closest = no_hit(ray);
    wide_.traverse(ray, TriangleTester(ray, kernel_), order_, closest, sink);
    return finish_query(closest, sink);
  }

  void for_each_node(const std::function<void(const NodeView&)>& fn) const override;
  NodeView node_view(NodeId id) const override;
  std::vector<uint32_t> node_prims(NodeId id) const override;

  // Volume policy used by Hierarchy (see hierarchy.h).
  static Aabb fit(const Scene&, const uint32_t*, size_t, const Aabb& box) { return box; }
  static float volume_area(const Aabb& box) { return box.area(); }
  static bool hit(const Aabb& box, const BoxTester& vray, const Ray&, float tmin, float tmax, float* t0, float* t1) {
    return vray.intersect(box, tmin, tmax, t0, t1);
  }
  static void describe(const Aabb&, NodeView*) {}

 protected:
  Status build_impl(const Scene& scene, const ParamSet& params) override;
  BuildStats compute_stats() const override;

 private:
  int width_ = 4;
  WideBvh wide_;
};

}  // namespace accel
