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

TriangleTester::TriangleTester(const Ray& ray, Kernel kernel) : ray_(ray), kernel_(kernel) {
  // Woop et al. 2013, section 3: permute so that kz is the dominant direction axis and the
  // winding is preserved, then shear so the ray becomes the +z axis. Written with selects,
  // not branches: the axes are random per ray, so a branch here was a misprediction.
  const Vec3 a(std::fabs(ray.dir.x), std::fabs(ray.dir.y), std::fabs(ray.dir.z));  // glm::abs branches
  const int xy = a.x >= a.y ? 0 : 1;
  kz_ = std::max(a.x, a.y) >= a.z ? xy : 2;  // max returns a.x on a tie, as xy chose
  static constexpr int kNext[3] = {1, 2, 0};
  const int x = kNext[kz_], y = kNext[x];
  const bool flip = component(ray.dir, kz_) < 0.0f;
  kx_ = flip ? y : x;
  ky_ = flip ? x : y;
  const float dz = component(ray.dir, kz_);
  sx_ = component(ray.dir, kx_) / dz;
  sy_ = component(ray.dir, ky_) / dz;
  sz_ = 1.0f / dz;
  org_kx_ = component(ray.org, kx_);
  org_ky_ = component(ray.org, ky_);
  org_kz_ = component(ray.org, kz_);
}

bool TriangleTester::reference(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax,
                               TriangleHit* out) const {
  double t, u, v;
  if (!intersect_triangle_double(ray_, p0, p1, p2, tmax, &t, &u, &v)) return false;
  *out = {float(t), float(u), float(v)};
  // A t beyond FLT_MAX (a subnormal direction: t in units of a tiny d) has no float answer.
  if (std::isinf(out->t)) return false;
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
  // 1/(-0.0) = -inf and 1/(+0.0) = +inf, so the slab test needs no special case.
  inv_dir = Vec3(1.0f / ray.dir.x, 1.0f / ray.dir.y, 1.0f / ray.dir.z);
  for (int axis = 0; axis < 3; ++axis) {
    const int negative = std::signbit(inv_dir[axis]) ? 1 : 0;
    near_index[axis] = axis + 3 * negative;
    far_index[axis] = axis + 3 * (1 - negative);
  }
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
