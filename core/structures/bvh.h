#pragma once
// Bounding volume hierarchy with axis-aligned boxes (AABB tree), registered as "bvh":
// its parameters, the factory that picks the layout by `width`, and the lecture's binary
// tree (BinaryBvh, width=2, traversals in hierarchy.h). The 4-wide SSE layout (WideBvh,
// width=4, the default because it is the fastest) is in wide_bvh.h; builders: bvh_builders.h.
#include <memory>

#include "structures/hierarchy.h"
#include "structures/wide_bvh.h"

namespace accel {

// Parameters of "bvh": bvh_param_specs() in hierarchy_params.h (the hierarchy's plus `width`,
// which picks the layout).
/// A new, unbuilt BVH of the layout `params` ask for: BinaryBvh for width=2, WideBvh for width=4.
std::unique_ptr<Structure> make_bvh(const ParamSet& params);

/// The lecture's binary AABB tree (bvh width=2): 32-byte nodes, one box test per child.
class BinaryBvh final : public Hierarchy<BinaryBvh, Aabb, BoxTester> {
 public:
  /// The registry name both layouts share.
  std::string name() const override { return "bvh"; }

  // Volume policy used by Hierarchy (see hierarchy.h).
  /// A leaf's box is the builder's box (already tight).
  static Aabb fit(const Scene&, const uint32_t*, size_t, const Aabb& box) { return box; }
  /// SAH surface area.
  static float volume_area(const Aabb& box) { return box.area(); }
  /// The slab test with the ray's precomputed reciprocal direction.
  static bool hit(const Aabb& box, const BoxTester& vray, const Ray&, float tmin, float tmax, float* t0, float* t1) {
    return vray.intersect(box, tmin, tmax, t0, t1);
  }
  /// Nothing beyond the box, which every NodeView has.
  static void describe(const Aabb&, NodeView*) {}

 protected:
  BuildStats compute_stats() const override;
};

}  // namespace accel
