#pragma once
// Bounding volume hierarchy with axis-aligned boxes (AABB tree). Builders: bvh_builders.h;
// traversal orders: hierarchy.h.
#include "hierarchy.h"

namespace accel {

class Bvh final : public Hierarchy<Bvh, Aabb, BoxTester> {
 public:
  static std::vector<ParamSpec> param_specs() { return hierarchy_param_specs(); }
  std::string name() const override { return "bvh"; }

  // Volume policy used by Hierarchy (see hierarchy.h).
  static Aabb fit(const Scene&, const uint32_t*, size_t, const Aabb& box) { return box; }
  static float volume_area(const Aabb& box) { return box.area(); }
  static bool hit(const Aabb& box, const BoxTester& vray, const Ray&, float tmin, float tmax, float* t0, float* t1) {
    return vray.intersect(box, tmin, tmax, t0, t1);
  }
  static void describe(const Aabb&, NodeView*) {}
};

}  // namespace accel
