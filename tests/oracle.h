#pragma once
// The correctness rule of ../shared/formats.md, as used by outside checks: the oracle every
// structure and kernel is compared against.
#include <cmath>
#include <string>
#include <vector>

#include "geometry.h"
#include "scene.h"

namespace accel::testing {

/// Closest hit by the double-precision reference kernel over all triangles.
struct ReferenceHit {
  int32_t prim = -1;
  double t = INFINITY;
};

inline ReferenceHit reference_closest(const Scene& scene, const Ray& ray) {
  ReferenceHit best;
  for (uint32_t prim : scene.valid_prims()) {
    double t, u, v;
    const double tmax = best.prim < 0 ? double(ray.tmax) : best.t;
    if (intersect_triangle_double(ray, scene.vertex(prim, 0), scene.vertex(prim, 1), scene.vertex(prim, 2), tmax, &t,
                                  &u, &v) &&
        (best.prim < 0 || t < best.t)) {
      best = {int32_t(prim), t};
    }
  }
  return best;
}

/// Distance from point p to triangle (a, b, c), in double (Ericson, Real-Time Collision
/// Detection 5.1.5, closest point on triangle).
inline double point_triangle_distance(const DVec3& p, const DVec3& a, const DVec3& b, const DVec3& c) {
  const DVec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
  const DVec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
  const DVec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return glm::length(p - (a + ab * v + ac * w));
}

/// formats.md's allowance: 8 float32 ulps of the scene's largest absolute coordinate M.
inline double ulp_allowance(const Scene& scene) {
  const double m = std::max(double(scene.max_abs_coordinate()), 1e-30);
  return 8.0 * std::ldexp(1.0, int(std::floor(std::log2(m))) - 23);
}

/// True when `got` is a correct answer for `ray` by formats.md's rule; otherwise `why` says why.
inline bool hit_is_correct(const Scene& scene, const Ray& ray, const Hit& got, const ReferenceHit& ref,
                           std::string* why = nullptr) {
  auto reason = [&](const std::string& s) {
    if (why) *why = s + " (got prim " + std::to_string(got.prim) + " t " + std::to_string(got.t) + ", ref prim " +
                    std::to_string(ref.prim) + " t " + std::to_string(ref.t) + ")";
    return false;
  };
  if (got.valid() != (ref.prim >= 0)) return reason(got.valid() ? "false hit" : "false miss");
  if (!got.valid()) return true;
  const double tol = 1e-4 * std::max(1.0, std::abs(ref.t));
  const double allowance = ulp_allowance(scene);
  const DVec3 point = DVec3(ray.org) + double(got.t) * DVec3(ray.dir);
  auto near_triangle = [&](int32_t prim) {
    return point_triangle_distance(point, DVec3(scene.vertex(prim, 0)), DVec3(scene.vertex(prim, 1)),
                                   DVec3(scene.vertex(prim, 2))) <= allowance;
  };
  const bool t_ok = std::abs(double(got.t) - ref.t) <= tol || near_triangle(ref.prim);
  if (!t_ok) return reason("t differs");
  if (got.prim == ref.prim) return true;
  // A tie: the returned triangle's own exact t must equal t_ref within the tolerance.
  double t, u, v;
  Ray unclipped = ray;
  unclipped.tmin = -INFINITY;
  unclipped.tmax = INFINITY;
  if (intersect_triangle_double(unclipped, scene.vertex(got.prim, 0), scene.vertex(got.prim, 1),
                                scene.vertex(got.prim, 2), INFINITY, &t, &u, &v) &&
      std::abs(t - ref.t) <= tol)
    return true;
  if (near_triangle(got.prim) && std::abs(double(got.t) - ref.t) <= tol) return true;
  return reason("wrong triangle");
}

}  // namespace accel::testing
