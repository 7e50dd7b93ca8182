#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "planar_geometry.h"

namespace accel {

std::string_view kernel_name(Kernel k) {
  switch (k) {
    case Kernel::Watertight: return "watertight";
    case Kernel::Moller: return "moller";
    case Kernel::Double: return "double";
    case Kernel::Planar: return "planar";
  }
  return "?";
}

bool parse_kernel(std::string_view name, Kernel* out) {
  for (Kernel k : kAllKernels) {
    if (name == kernel_name(k)) { *out = k; return true; }
  }
  return false;
}

std::string kernel_names_text(std::string_view separator) {
  std::string s;
  for (Kernel k : kAllKernels) s += (s.empty() ? "" : std::string(separator)) + std::string(kernel_name(k));
  return s;
}

bool TriangleTester::reference(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax,
                               TriangleHit* out) const {
  double t, u, v;
  if (!intersect_triangle_double(ray_, p0, p1, p2, tmax, &t, &u, &v)) return false;
  return float_answer(t, u, v, tmax, out);
}

int TriangleTester::scalar4(const TriangleBlock& block, int lanes, float tmax, float* t, float* u,
                            float* v) const {
  // Double and planar have no SIMD form; lane by lane.
  return test_lanes(block, lanes, tmax, t, u, v,
                    [this](const Vec3& p0, const Vec3& p1, const Vec3& p2, float t_max, TriangleHit* h) {
                      return intersect(p0, p1, p2, t_max, h);
                    });
}

int TriangleTester::reference4(const TriangleBlock& block, int lanes, float tmax, float* t, float* u,
                               float* v) const {
  return test_lanes(block, lanes, tmax, t, u, v,
                    [this](const Vec3& p0, const Vec3& p1, const Vec3& p2, float t_max, TriangleHit* h) {
                      return reference(p0, p1, p2, t_max, h);
                    });
}

bool TriangleTester::float_answer(double t, double u, double v, float tmax, TriangleHit* out) const {
  *out = {float(t), float(u), float(v)};
  // A t beyond FLT_MAX (a subnormal direction: t in units of a tiny d) has no float answer.
  if (std::isinf(out->t)) return false;
  // Rounding t to float may push it past an inclusive bound; keep the float answer inside.
  out->t = std::clamp(out->t, ray_.tmin, tmax);
  return true;
}

bool TriangleTester::planar(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const {
  // A ray leaving the plane (the viewer's perspective rays onto a 2D scene) meets it at one
  // point, as it meets any flat scene: the 3D rule (docs/hits.md, 2D scenes).
  if (!is_planar_ray(ray_)) return reference(p0, p1, p2, tmax, out);
  double t, u, v;
  if (!PlanarRayTester(ray_).intersect(p0, p1, p2, tmax, &t, &u, &v)) return false;
  return float_answer(t, u, v, tmax, out);
}

DoubleRayTester::DoubleRayTester(const Ray& ray) : tmin_(ray.tmin) {
  const DVec3 dir(ray.dir);
  const DVec3 ad = glm::abs(dir);
  kz_ = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
  kx_ = (kz_ + 1) % 3;
  ky_ = (kx_ + 1) % 3;
  if (dir[kz_] < 0.0) std::swap(kx_, ky_);
  zero_dir_ = dir[kz_] == 0.0;
  if (zero_dir_) return;
  sx_ = dir[kx_] / dir[kz_];
  sy_ = dir[ky_] / dir[kz_];
  sz_ = 1.0 / dir[kz_];
  const DVec3 org(ray.org);
  org_k_[0] = org[kx_];
  org_k_[1] = org[ky_];
  org_k_[2] = org[kz_];
}

bool DoubleRayTester::intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, double tmax, double* t_out,
                                double* u_out, double* v_out) const {
  if (zero_dir_) return false;
  // Coordinates picked by index from arrays: glm's operator[] is a switch per access.
  const float q0[3] = {p0.x, p0.y, p0.z}, q1[3] = {p1.x, p1.y, p1.z}, q2[3] = {p2.x, p2.y, p2.z};
  const double a_x = double(q0[kx_]) - org_k_[0], a_y = double(q0[ky_]) - org_k_[1], a_z = double(q0[kz_]) - org_k_[2];
  const double b_x = double(q1[kx_]) - org_k_[0], b_y = double(q1[ky_]) - org_k_[1], b_z = double(q1[kz_]) - org_k_[2];
  const double c_x = double(q2[kx_]) - org_k_[0], c_y = double(q2[ky_]) - org_k_[1], c_z = double(q2[kz_]) - org_k_[2];
  const double ax = a_x - sx_ * a_z, ay = a_y - sy_ * a_z;
  const double bx = b_x - sx_ * b_z, by = b_y - sy_ * b_z;
  const double cx = c_x - sx_ * c_z, cy = c_y - sy_ * c_z;
  const double u = cx * by - cy * bx;
  const double v = ax * cy - ay * cx;
  const double w = bx * ay - by * ax;
  // Bitwise, not short-circuit: one well-predicted branch (almost every triangle misses).
  const bool negative = (u < 0.0) | (v < 0.0) | (w < 0.0), positive = (u > 0.0) | (v > 0.0) | (w > 0.0);
  if (negative & positive) return false;
  const double det = u + v + w;
  if (det == 0.0) return false;
  const double t = (u * sz_ * a_z + v * sz_ * b_z + w * sz_ * c_z) / det;
  if (!(t >= tmin_ && t <= tmax)) return false;
  *t_out = t;
  *u_out = v / det;
  *v_out = w / det;
  return true;
}

bool intersect_triangle_double(const Ray& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                               double tmax, double* t_out, double* u_out, double* v_out) {
  return DoubleRayTester(ray).intersect(p0, p1, p2, tmax, t_out, u_out, v_out);
}

bool is_degenerate(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const DVec3 e1 = DVec3(p1) - DVec3(p0), e2 = DVec3(p2) - DVec3(p0);
  const DVec3 n = glm::cross(e1, e2);
  return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

bool intersect_sphere(const Ray& ray, const BoundingSphere& s, float tmin, float tmax, float* t_enter,
                      float* t_exit) {
  if (s.empty()) return false;
  // Solve |o + t d - c|^2 = r^2 in double: robust for rays far from the sphere.
  const DVec3 oc = DVec3(ray.org) - DVec3(s.center);
  const DVec3 d(ray.dir);
  const double a = glm::dot(d, d);
  if (a == 0.0) return false;
  const double r = double(s.radius) * (1.0 + 4.0 * double(gamma_bound(3)));
  // Project the centre onto the ray first (Hearn-Baker / Ray Tracing Gems ch. 7 form),
  // which avoids cancellation in b^2 - ac.
  const double t_mid = -glm::dot(oc, d) / a;
  const DVec3 closest = oc + t_mid * d;
  const double disc = r * r - glm::dot(closest, closest);
  if (disc < 0.0) return false;
  const double half = std::sqrt(disc / a);
  const double t0 = t_mid - half, t1 = t_mid + half;
  const float lo = std::max(tmin, float(t0) * (t0 > 0 ? 1.0f - 2.0f * gamma_bound(3) : 1.0f + 2.0f * gamma_bound(3)));
  const float hi = std::min(tmax, float(t1) * (t1 > 0 ? 1.0f + 2.0f * gamma_bound(3) : 1.0f - 2.0f * gamma_bound(3)));
  if (lo > hi) return false;
  *t_enter = lo;
  *t_exit = hi;
  return true;
}

}  // namespace accel
