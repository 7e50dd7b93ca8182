#pragma once
// Bounding volume hierarchy with bounding spheres. Same builders and traversal orders as
// the AABB tree (hierarchy.h). The spheres are fitted bottom-up, children before parents:
//  - a node with at most kDirectFit triangles below it: Ritter's algorithm (Ritter 1990,
//    "An efficient bounding sphere", Graphics Gems) over their vertices, its radius then
//    tightened to the farthest vertex, and replaced by the box's circumsphere when that is
//    smaller (fit());
//  - a larger node (fit_inner()): candidate centres from the children's spheres (the centre
//    of the smallest sphere around both) and from the box, each with the exact radius, the
//    distance to its farthest vertex below, found by a branch-and-bound search over the
//    children's spheres (a subtree whose sphere cannot reach beyond the farthest vertex
//    found so far is skipped), and Ritter's first guess (a diameter's midpoint) found by the
//    same search; then a few steps of the centre towards its farthest vertex (Badoiu &
//    Clarkson 2003) while the radius shrinks.
// Every radius is a distance to a real vertex, so every sphere holds its triangles however
// loose a child's is; the children's spheres only steer the search. Fitting each node
// to all vertices below it with Ritter (before issue #31) passed over every vertex once per
// level. A refit (hierarchy_refit.cpp) fits the spheres of the same nodes in exactly this way.
#include <limits>

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
  /// Nodes with at most this many triangles below are fitted by fit(), larger ones by fit_inner().
  static constexpr size_t kDirectFit = 32;
  /// The sphere of inner node `k` from its subtree, whose spheres are fitted already.
  BoundingSphere fit_inner(uint32_t k) const;
  /// Surface area: the SAH's hit probability is proportional to it for any convex volume.
  static float volume_area(const BoundingSphere& s) { return 4.0f * 3.14159265f * s.radius * s.radius; }
  static bool hit(const BoundingSphere& s, const SphereRay&, const Ray& ray, float tmin, float tmax, float* t0,
                  float* t1) {
    return intersect_sphere(ray, s, tmin, tmax, t0, t1);
  }
  static void describe(const BoundingSphere& s, NodeView* v) { v->sphere = s; }

 protected:
  BuildStats compute_stats() const override;

 private:
  struct Farthest {
    double distance = -1.0;
    DVec3 vertex{0.0};
  };
  /// The vertex below node `k` farthest from `centre` (branch and bound over the spheres),
  /// starting from `known` (a vertex below `k`) when given; gives up and returns the first
  /// vertex found at `give_up` or farther.
  Farthest farthest_vertex(uint32_t k, const DVec3& centre,
                           double give_up = std::numeric_limits<double>::infinity(),
                           const DVec3* known = nullptr) const;
};

}  // namespace accel
