// Clipping triangles to boxes (lecture, kd-tree: "some polygons need to be assigned to both
// children"): the kd-tree builder's perfect splits, after Havran 2000, "Heuristic ray
// shooting algorithms" and Wald & Havran 2006, "On building fast kd-trees for ray tracing,
// and on doing that in O(N log N)", sec. 4.3.
#include "structures/kd_clipping.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "float_steps.h"

namespace accel::kd {

bool clip_triangle_bounds(const Scene& scene, uint32_t prim, const Aabb& box, Aabb* out) {
  const Aabb& tri = scene.triangle_bounds(prim);
  Aabb cut;
  cut.min = glm::max(tri.min, box.min);
  cut.max = glm::min(tri.max, box.max);
  if (cut.empty()) return false;
  if (box.contains(tri)) {  // nothing to clip
    *out = tri;
    return true;
  }
  // The largest magnitude of a coordinate, in float (a float's magnitude converts to double
  // exactly, so the maximum is the same either way).
  const Vec3 mags =
      glm::max(glm::max(glm::abs(tri.min), glm::abs(tri.max)), glm::max(glm::abs(box.min), glm::abs(box.max)));
  const double m = double(std::max({mags.x, mags.y, mags.z}));
  const double delta = std::max(m, 1e-30) * 0x1p-30;  // exact, as ldexp(., -30)

  // A triangle clipped by 6 planes has at most 3 + 6 vertices. A plane that every vertex lies
  // inside would copy the polygon unchanged, so it is skipped (most planes of a straddler's
  // clip: only the split plane and the region's faces it crosses cut it).
  DVec3 buf[2][10];
  DVec3* poly = buf[0];
  DVec3* next = buf[1];
  int n = 3;
  for (int k = 0; k < 3; ++k) poly[k] = DVec3(scene.vertex(prim, k));
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      // The triangle's own bounds inside this face: every vertex is inside by at least
      // delta, far more than the rounding of the points earlier planes made (a few ulps of
      // m), so the test below would find all inside: skipped without it.
      if (side == 0 ? tri.min[axis] >= box.min[axis] : tri.max[axis] <= box.max[axis]) continue;
      const double plane = side == 0 ? double(box.min[axis]) - delta : double(box.max[axis]) + delta;
      bool in[10];
      int inside = 0;
      for (int i = 0; i < n; ++i) {
        in[i] = side == 0 ? poly[i][axis] >= plane : poly[i][axis] <= plane;
        inside += in[i];
      }
      if (inside == n) continue;
      if (inside == 0) return false;  // the enlarged box misses the triangle
      int m_out = 0;
      for (int i = 0; i < n; ++i) {
        const int j = i + 1 == n ? 0 : i + 1;
        const DVec3& a = poly[i];
        const DVec3& b = poly[j];
        if (in[i]) next[m_out++] = a;
        if (in[i] != in[j]) {
          const double s = (plane - a[axis]) / (b[axis] - a[axis]);
          DVec3 q = a + s * (b - a);
          q[axis] = plane;
          next[m_out++] = q;
        }
      }
      n = m_out;
      std::swap(poly, next);
    }
  }
  DVec3 lo = poly[0], hi = poly[0];
  for (int i = 1; i < n; ++i) {
    lo = glm::min(lo, poly[i]);
    hi = glm::max(hi, poly[i]);
  }
  Aabb b;
  for (int k = 0; k < 3; ++k) {
    b.min[k] = std::max(float_down(lo[k] - delta), cut.min[k]);
    b.max[k] = std::min(float_up(hi[k] + delta), cut.max[k]);
  }
  if (b.empty()) return false;  // the enlarged clip lies outside the exact bounds: a miss
  *out = b;
  return true;
}

}  // namespace accel::kd
