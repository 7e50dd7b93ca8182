#pragma once
// Brute force: tests every triangle. The oracle of every structure test and the floor
// of every benchmark. It implements Structure like the others, so it is also shown in the
// viewer (one "node": the scene box).
#include "structure.h"

namespace accel {

class BruteForce final : public StructureWithTraversal<BruteForce> {
 public:
  static std::vector<ParamSpec> param_specs() { return {}; }
  std::string name() const override { return "brute"; }
  void for_each_node(const std::function<void(const NodeView&)>& fn) const override;
  NodeView node_view(NodeId id) const override;
  std::vector<uint32_t> node_prims(NodeId id) const override;

  /// The one traversal: a linear scan over the non-degenerate triangles.
  template <TraversalSink Sink>
  Hit traverse(const Ray& ray, Sink& sink) const {
    const TriangleTester tester(ray, kernel_);
    Hit closest = no_hit(ray);
    sink.visit(0, 0, ray.tmin, ray.tmax);
    if (scene_)  // null when unbuilt or cancelled: every ray misses
      for (uint32_t prim : scene_->valid_prims()) test_triangle(*scene_, tester, prim, closest, sink);
    return finish_query(closest, sink);
  }

 protected:
  Status build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) override;
  BuildStats compute_stats() const override { return stats_; }

 private:
  const Scene* scene_ = nullptr;
  BuildStats stats_;
};

}  // namespace accel
