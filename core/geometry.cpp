#include "geometry.h"

#include <cmath>
#include <utility>

namespace accel {

std::string_view kernel_name(Kernel k) {
  switch (k) {
    case Kernel::Watertight: return "watertight";
    case Kernel::Moller: return "moller";
    case Kernel::Double: return "double";
  }
  return "?";
}

bool parse_kernel(std::string_view name, Kernel* out) {
  for (Kernel k : {Kernel::Watertight, Kernel::Moller, Kernel::Double}) {
    if (name == kernel_name(k)) { *out = k; return true; }
  }
  return false;
}

TriangleTester::TriangleTester(const Ray& ray, Kernel kernel) : ray_(ray), kernel_(kernel) {
  // Woop et al. 2013, section 3: permute so that kz is the dominant direction axis and the
  // winding is preserved, then shear so the ray becomes the +z axis.
  const Vec3 a = glm::abs(ray.dir);
  kz_ = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
  kx_ = (kz_ + 1) % 3;
  ky_ = (kx_ + 1) % 3;
  if (ray.dir[kz_] < 0.0f) std::swap(kx_, ky_);
  sx_ = ray.dir[kx_] / ray.dir[kz_];
  sy_ = ray.dir[ky_] / ray.dir[kz_];
  sz_ = 1.0f / ray.dir[kz_];
}

bool TriangleTester::intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax,
                               TriangleHit* out) const {
  switch (kernel_) {
    case Kernel::Watertight: return watertight(p0, p1, p2, tmax, out);
    case Kernel::Moller: return moller(p0, p1, p2, tmax, out);
    case Kernel::Double: return reference(p0, p1, p2, tmax, out);
  }
  return false;
}

bool TriangleTester::watertight(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax,
                                TriangleHit* out) const {
  const Vec3 a = p0 - ray_.org, b = p1 - ray_.org, c = p2 - ray_.org;
  const float ax = a[kx_] - sx_ * a[kz_], ay = a[ky_] - sy_ * a[kz_];
  const float bx = b[kx_] - sx_ * b[kz_], by = b[ky_] - sy_ * b[kz_];
  const float cx = c[kx_] - sx_ * c[kz_], cy = c[ky_] - sy_ * c[kz_];
  // Scaled barycentrics: u_ weights p0, v_ weights p1, w_ weights p2.
  const float u_ = cx * by - cy * bx;
  const float v_ = ax * cy - ay * cx;
  const float w_ = bx * ay - by * ax;
  // The float edge functions carry rounding errors from the translation, the shear and the
  // products. Where one of them is within its error bound of zero (the ray passes within
  // float precision of an edge or vertex), its sign is unknown and the double-precision test
  // decides -- the paper's fallback for an exact zero, widened to the whole uncertain band.
  // Both triangles of a shared edge fall back together, so the result stays watertight.
  // Bound: each sheared coordinate is off by at most ~4 eps of its unsheared magnitude m,
  // so an edge function (products of sheared coordinates s) is off by ~8 eps (m s' + s m').
  const float sxa = std::abs(sx_), sya = std::abs(sy_);
  const float m_a = std::abs(a[kx_]) + std::abs(a[ky_]) + (sxa + sya) * std::abs(a[kz_]);
  const float m_b = std::abs(b[kx_]) + std::abs(b[ky_]) + (sxa + sya) * std::abs(b[kz_]);
  const float m_c = std::abs(c[kx_]) + std::abs(c[ky_]) + (sxa + sya) * std::abs(c[kz_]);
  const float s_a = std::abs(ax) + std::abs(ay), s_b = std::abs(bx) + std::abs(by), s_c = std::abs(cx) + std::abs(cy);
  const float bound =
      10.0f * gamma_bound(1) * (m_a * (s_b + s_c) + m_b * (s_a + s_c) + m_c * (s_a + s_b));
  const bool some_negative = u_ < -bound || v_ < -bound || w_ < -bound;
  const bool some_positive = u_ > bound || v_ > bound || w_ > bound;
  if (some_negative && some_positive) return false;  // certainly outside
  if (std::abs(u_) <= bound || std::abs(v_) <= bound || std::abs(w_) <= bound)
    return reference(p0, p1, p2, tmax, out);
  const float det = u_ + v_ + w_;
  if (det == 0.0f) return false;  // ray lies in the triangle's plane (or is parallel to it)
  const float az = sz_ * a[kz_], bz = sz_ * b[kz_], cz = sz_ * c[kz_];
  const float t_scaled = u_ * az + v_ * bz + w_ * cz;
  const float inv_det = 1.0f / det;
  const float t = t_scaled * inv_det;
  // t carries a rounding error of a few ulps of the terms summed into it. Close to tmin or
  // tmax that error can flip the inclusive range test (origins on a surface, hits exactly
  // at tmax), so there, and only there, the double-precision test decides.
  const float t_err = 64.0f * gamma_bound(1) * (std::abs(u_ * az) + std::abs(v_ * bz) + std::abs(w_ * cz)) *
                      std::abs(inv_det);
  if (t - t_err <= ray_.tmin || t + t_err >= tmax) return reference(p0, p1, p2, tmax, out);
  *out = {t, v_ * inv_det, w_ * inv_det};
  return true;
}

bool TriangleTester::moller(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax,
                            TriangleHit* out) const {
  // Moller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection".
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const Vec3 pv = glm::cross(ray_.dir, e2);
  const float det = glm::dot(e1, pv);
  if (det == 0.0f) return false;
  const float inv_det = 1.0f / det;
  const Vec3 tv = ray_.org - p0;
  const float u = glm::dot(tv, pv) * inv_det;
  if (u < 0.0f || u > 1.0f) return false;
  const Vec3 qv = glm::cross(tv, e1);
  const float v = glm::dot(ray_.dir, qv) * inv_det;
  if (v < 0.0f || u + v > 1.0f) return false;
  const float t = glm::dot(e2, qv) * inv_det;
  if (!(t >= ray_.tmin && t <= tmax)) return false;
  *out = {t, u, v};
  return true;
}

bool TriangleTester::reference(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax,
                               TriangleHit* out) const {
  double t, u, v;
  if (!intersect_triangle_double(ray_, p0, p1, p2, tmax, &t, &u, &v)) return false;
  *out = {float(t), float(u), float(v)};
  // Rounding t to float may push it past an inclusive bound; keep the float answer inside.
  out->t = std::clamp(out->t, ray_.tmin, tmax);
  return true;
}

bool intersect_triangle_double(const Ray& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                               double tmax, double* t_out, double* u_out, double* v_out) {
  const DVec3 dir(ray.dir), org(ray.org);
  const DVec3 ad = glm::abs(dir);
  int kz = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (dir[kz] < 0.0) std::swap(kx, ky);
  if (dir[kz] == 0.0) return false;  // zero direction: no well-defined hit
  const double sx = dir[kx] / dir[kz], sy = dir[ky] / dir[kz], sz = 1.0 / dir[kz];
  const DVec3 a = DVec3(p0) - org, b = DVec3(p1) - org, c = DVec3(p2) - org;
  const double ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
  const double bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
  const double cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
  const double u = cx * by - cy * bx;
  const double v = ax * cy - ay * cx;
  const double w = bx * ay - by * ax;
  if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
  const double det = u + v + w;
  if (det == 0.0) return false;
  const double t = (u * sz * a[kz] + v * sz * b[kz] + w * sz * c[kz]) / det;
  if (!(t >= double(ray.tmin) && t <= tmax)) return false;
  *t_out = t;
  *u_out = v / det;
  *v_out = w / det;
  return true;
}

bool is_degenerate(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const DVec3 e1 = DVec3(p1) - DVec3(p0), e2 = DVec3(p2) - DVec3(p0);
  const DVec3 n = glm::cross(e1, e2);
  return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

BoxTester::BoxTester(const Ray& ray) : org(ray.org) {
  // 1/(-0.0) = -inf and 1/(+0.0) = +inf, so the slab test below needs no special case.
  inv_dir = Vec3(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z);
}

bool BoxTester::intersect(const Aabb& box, float tmin, float tmax, float* t_enter, float* t_exit) const {
  constexpr float widen = 1.0f + 2.0f * gamma_bound(3);
  for (int axis = 0; axis < 3; ++axis) {
    // Order the slabs by the sign of the direction, not by comparing the distances: with
    // -0.0 one distance may be NaN and a comparison would pick the wrong side.
    const bool negative = std::signbit(inv_dir[axis]);
    const float t_near = ((negative ? box.max[axis] : box.min[axis]) - org[axis]) * inv_dir[axis];
    const float t_far = ((negative ? box.min[axis] : box.max[axis]) - org[axis]) * inv_dir[axis] * widen;
    // Written so a NaN (0 * inf: origin on a slab plane, zero direction) leaves the
    // interval unchanged instead of poisoning it.
    tmin = t_near > tmin ? t_near : tmin;
    tmax = t_far < tmax ? t_far : tmax;
    if (tmin > tmax) return false;
  }
  *t_enter = tmin;
  *t_exit = tmax;
  return true;
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
