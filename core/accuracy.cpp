#include "accuracy.h"

#include <algorithm>

#include "planar_geometry.h"

namespace accel {

const char* verdict_name(HitVerdict v) {
  switch (v) {
    case HitVerdict::Correct: return "correct";
    case HitVerdict::FalseMiss: return "false miss";
    case HitVerdict::FalseHit: return "false hit";
    case HitVerdict::WrongPrim: return "wrong triangle";
    case HitVerdict::WrongT: return "t differs";
  }
  return "?";
}

namespace {

/// The closest hit by `tester` (DoubleRayTester or PlanarRayTester) over every valid triangle.
template <class Tester>
ReferenceHit closest_by(const Scene& scene, const Ray& ray, const Tester& tester) {
  ReferenceHit best;
  for (uint32_t prim : scene.valid_prims()) {
    double t, u, v;
    const double tmax = best.prim < 0 ? double(ray.tmax) : best.t;
    if (tester.intersect(scene.vertex(prim, 0), scene.vertex(prim, 1), scene.vertex(prim, 2), tmax, &t, &u, &v) &&
        (best.prim < 0 || t < best.t)) {
      best = {int32_t(prim), t};
    }
  }
  return best;
}

/// The exact (double) t of `ray` on triangle `prim` by the scene's hit rule, if it hits.
bool exact_t(const Scene& scene, const Ray& ray, uint32_t prim, double* t) {
  double u, v;
  const Vec3 &a = scene.vertex(prim, 0), &b = scene.vertex(prim, 1), &c = scene.vertex(prim, 2);
  if (scene.planar() && is_planar_ray(ray)) return PlanarRayTester(ray).intersect(a, b, c, INFINITY, t, &u, &v);
  return intersect_triangle_double(ray, a, b, c, INFINITY, t, &u, &v);
}

}  // namespace

ReferenceHit reference_closest(const Scene& scene, const Ray& ray) {
  if (scene.planar() && is_planar_ray(ray)) return closest_by(scene, ray, PlanarRayTester(ray));
  return closest_by(scene, ray, DoubleRayTester(ray));
}

double point_triangle_distance(const DVec3& p, const DVec3& a, const DVec3& b, const DVec3& c) {
  // Ericson, Real-Time Collision Detection, 5.1.5: closest point on a triangle by regions.
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
  return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

double ulp_allowance(const Scene& scene) {
  const double m = std::max(double(scene.max_abs_coordinate()), 1e-30);
  return 8.0 * std::ldexp(1.0, int(std::floor(std::log2(m))) - 23);
}

HitVerdict judge_hit(const Scene& scene, const Ray& ray, const Hit& got, const ReferenceHit& ref) {
  if (got.valid() != (ref.prim >= 0)) return got.valid() ? HitVerdict::FalseHit : HitVerdict::FalseMiss;
  if (!got.valid()) return HitVerdict::Correct;
  const double tol = 1e-4 * std::max(1.0, std::abs(ref.t));
  const DVec3 point = DVec3(ray.org) + double(got.t) * DVec3(ray.dir);
  const double allowance = ulp_allowance(scene);
  auto near_triangle = [&](int32_t prim) {
    return point_triangle_distance(point, DVec3(scene.vertex(prim, 0)), DVec3(scene.vertex(prim, 1)),
                                   DVec3(scene.vertex(prim, 2))) <= allowance;
  };
  const bool t_close = std::abs(double(got.t) - ref.t) <= tol;
  if (!t_close && !near_triangle(ref.prim)) return HitVerdict::WrongT;
  if (got.prim == ref.prim) return HitVerdict::Correct;
  // A tie: the returned triangle's own exact t equals t_ref within the tolerance.
  Ray unclipped = ray;
  unclipped.tmin = -INFINITY;
  unclipped.tmax = INFINITY;
  double t;
  if (exact_t(scene, unclipped, uint32_t(got.prim), &t) && std::abs(t - ref.t) <= tol)
    return HitVerdict::Correct;
  if (t_close && near_triangle(got.prim)) return HitVerdict::Correct;
  return HitVerdict::WrongPrim;
}

}  // namespace accel
