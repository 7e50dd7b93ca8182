#pragma once
// Bounding volume hierarchy with bounding spheres. Same builders and traversal orders as
// the AABB tree (hierarchy.h); each node's sphere is fitted to the vertices of all
// triangles below it with Ritter's algorithm (Ritter 1990, "An efficient bounding sphere",
// Graphics Gems), its radius then tightened to the farthest vertex, and replaced by the
// box's circumsphere when that is smaller. A refit (hierarchy_refit.cpp) fits the spheres
// of the same nodes to moved vertices in exactly this way.
#include "structures/hierarchy.h"

namespace accel {

/// The sphere test needs no per-ray precomputation.
struct SphereRay {
  explicit SphereRay(const Ray&) {}
};

class SphereTree final : public Hierarchy<SphereTree, BoundingSphere, SphereRay> {
 public:
  static std::vector<ParamSpec> param_specs() { return hierarchy_param_specs(); }
  std::string name() const override { return "spheretree"; }

  // Volume policy used by Hierarchy (see hierarchy.h).
  static BoundingSphere fit(const Scene& scene, const uint32_t* prims, size_t n, const Aabb& box);
  /// Surface area: the SAH's hit probability is proportional to it for any convex volume.
  static float volume_area(const BoundingSphere& s) { return 4.0f * 3.14159265f * s.radius * s.radius; }
  static bool hit(const BoundingSphere& s, const SphereRay&, const Ray& ray, float tmin, float tmax, float* t0,
                  float* t1) {
    return intersect_sphere(ray, s, tmin, tmax, t0, t1);
  }
  static void describe(const BoundingSphere& s, NodeView* v) { v->sphere = s; }

 protected:
  BuildStats compute_stats() const override;
};

}  // namespace accel
