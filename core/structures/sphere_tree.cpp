#include "structures/sphere_tree.h"

#include <cstdio>
#include <vector>

namespace accel {

BoundingSphere SphereTree::fit(const Scene& scene, const uint32_t* prims, size_t n, const Aabb& box) {
  if (n == 0) return {};
  // The vertices gathered once in double: the five passes below then read one contiguous
  // array instead of chasing triangle and vertex indices each time (the same values in the
  // same order, so the same sphere). Small nodes (most of them) on the stack.
  const size_t m = 3 * n;
  constexpr size_t kOnStack = 3 * 64;
  DVec3 small[kOnStack];
  std::vector<DVec3> large(m > kOnStack ? m : 0);
  DVec3* points = m > kOnStack ? large.data() : small;
  for (size_t k = 0; k < m; ++k) points[k] = DVec3(scene.vertex(prims[k / 3], int(k % 3)));
  auto vertex = [points](size_t k) { return points[k]; };
  // Ritter: from an arbitrary point find the farthest point a, from a the farthest b; start
  // with the sphere on diameter ab and grow it to include every point outside.
  const DVec3 p0 = vertex(0);
  DVec3 a = p0, b = p0;
  double best = -1.0;
  for (size_t k = 0; k < m; ++k)
    if (const double d = glm::length(vertex(k) - p0); d > best) { best = d; a = vertex(k); }
  best = -1.0;
  for (size_t k = 0; k < m; ++k)
    if (const double d = glm::length(vertex(k) - a); d > best) { best = d; b = vertex(k); }
  DVec3 c = 0.5 * (a + b);
  double r = 0.5 * glm::length(b - a);
  for (size_t k = 0; k < m; ++k) {
    const DVec3 p = vertex(k);
    const double d = glm::length(p - c);
    if (d > r) {
      const double nr = 0.5 * (r + d);
      c += (nr - r) / d * (p - c);
      r = nr;
    }
  }
  // Tighten to the farthest vertex from the final centre (Ritter's growth overshoots).
  double r2 = 0.0;
  for (size_t k = 0; k < m; ++k) r2 = std::max(r2, glm::length(vertex(k) - c));
  const DVec3 bc(box.center());
  const double box_r = 0.5 * glm::length(DVec3(box.extent()));
  if (box_r < r2) {
    c = bc;
    r2 = 0.0;
    for (size_t k = 0; k < m; ++k) r2 = std::max(r2, glm::length(vertex(k) - c));
  }
  // Round outward: the float centre moved by rounding; add that error and a relative ulp.
  const Vec3 cf(c);
  const double shift = glm::length(DVec3(cf) - c);
  return {cf, float((r2 + shift) * (1.0 + 1e-6)) + 1e-30f};
}

BuildStats SphereTree::compute_stats() const {
  BuildStats s = Hierarchy::compute_stats();
  double sphere_volume = 0.0, box_volume = 0.0;
  for (size_t i = 0; i < nodes_.size(); ++i) {
    const double r = nodes_[i].volume.radius;
    sphere_volume += 4.0 / 3.0 * 3.14159265358979 * r * r * r;
    box_volume += double(boxes_[i].volume());
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", box_volume > 0.0 ? sphere_volume / box_volume : 0.0);
  s.extra.push_back({"sphere_to_box_volume", buf});
  s.extra.push_back({"fit", "Ritter 1990, tightened; box circumsphere when smaller"});
  return s;
}

}  // namespace accel
