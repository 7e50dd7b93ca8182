#pragma once
// STUB: replaced by the real implementation.
#include "structure.h"

namespace accel {

class KdTree final : public StructureWithTraversal<KdTree> {
 public:
  static std::vector<ParamSpec> param_specs() { return {}; }
  std::string name() const override { return "kdtree"; }
  void for_each_node(const std::function<void(const NodeView&)>&) const override {}
  NodeView node_view(NodeId) const override { return {}; }
  std::vector<uint32_t> node_prims(NodeId) const override { return {}; }

  template <class Sink>
  Hit traverse(const Ray& ray, Sink& sink) const {
    const TriangleTester tester(ray, kernel_);
    Hit closest = no_hit(ray);
    for (uint32_t prim : scene_->valid_prims()) test_triangle(*scene_, tester, prim, closest, sink);
    const Hit result = finish_hit(closest);
    sink.done(result);
    return result;
  }

 protected:
  Result<bool> build_impl(const Scene& scene, const ParamSet&) override { scene_ = &scene; return true; }
  BuildStats compute_stats() const override { return {}; }

 private:
  const Scene* scene_ = nullptr;
};

}  // namespace accel
