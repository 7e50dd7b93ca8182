#pragma once
// Ray/triangle, ray/box and ray/sphere tests, following the hit rule of
// ../shared/formats.md: closed triangles (edges and vertices hit), tmin <= t <= tmax
// inclusive, never a zero-area triangle, never a triangle whose plane contains the ray.
#include <cmath>
#include <cstdint>
#include <string_view>
#include <utility>

#include "math.h"

namespace accel {

/// The closest hit of a query: prim = -1 and t = inf for a miss. The hit point is
/// (1-u-v)*v0 + u*v1 + v*v2.
struct Hit {
  int32_t prim = -1;
  float t = kInf;
  float u = 0.0f;
  float v = 0.0f;
  bool valid() const { return prim >= 0; }
};

/// Which ray/triangle test a query uses.
enum class Kernel : uint8_t {
  Watertight,  ///< Woop, Benthin, Wald 2013, "Watertight Ray/Triangle Intersection", float (default)
  Moller,      ///< Moller & Trumbore 1997 in float: fast, not watertight at shared edges
  Double,      ///< the watertight algorithm in double precision: the reference
};
std::string_view kernel_name(Kernel k);
/// Parses "watertight" / "moller" / "double"; false for anything else.
bool parse_kernel(std::string_view name, Kernel* out);

/// Result of one triangle test.
struct TriangleHit {
  float t, u, v;
};

/// A ray prepared for repeated triangle tests with one kernel (per-ray shear constants of
/// the watertight test are computed once here, not per triangle).
class TriangleTester {
 public:
  TriangleTester(const Ray& ray, Kernel kernel);
  /// True when the ray hits triangle (p0,p1,p2) at some t in [ray.tmin, tmax]; fills `out`.
  /// The caller guarantees the triangle has non-zero area (Scene marks degenerate ones).
  ACCEL_FORCE_INLINE bool intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  Kernel kernel() const { return kernel_; }

 private:
  // Inline: they run in every structure's innermost loop.
  ACCEL_FORCE_INLINE bool watertight(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  inline bool moller(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  bool reference(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;

  Ray ray_;
  Kernel kernel_;
  int kx_, ky_, kz_;     // axis permutation: kz is the largest |dir| component
  float sx_, sy_, sz_;   // shear constants
};

/// Double-precision watertight test of float inputs: the oracle used by tests and the
/// bench's error columns. Returns true and t,u,v on a hit in [tmin, tmax].
bool intersect_triangle_double(const Ray& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                               double tmax, double* t, double* u, double* v);

/// True when the triangle has exactly zero area (cross product of its float edges, taken in
/// double, is the zero vector). formats.md: such triangles are never hit.
bool is_degenerate(const Vec3& p0, const Vec3& p1, const Vec3& p2);

/// A ray prepared for slab tests: reciprocal direction with -0.0 giving -inf.
struct BoxTester {
  explicit BoxTester(const Ray& ray);
  /// Clips [tmin, tmax] to the box. Conservative (Ize 2013): the far distance is widened by
  /// 1 + 2*gamma(3) so rounding never loses a hit on a box face; a zero direction component
  /// with the origin on a slab plane gives no NaN (Williams et al. 2005).
  ACCEL_FORCE_INLINE bool intersect(const Aabb& box, float tmin, float tmax, float* t_enter, float* t_exit) const;
  Vec3 org, inv_dir;
  int negative[3];  ///< 1 where the direction's sign bit is set (-0.0 included)
};

/// Entry/exit distances of the ray through a sphere, clipped to [tmin, tmax]; conservative
/// (radius widened by a few ulps) so no enclosed hit is culled.
bool intersect_sphere(const Ray& ray, const BoundingSphere& s, float tmin, float tmax, float* t_enter,
                      float* t_exit);

/// gamma(n) = n*eps / (1 - n*eps) with eps = 2^-24 (pbrt's bound on n float roundings).
constexpr float gamma_bound(int n) {
  constexpr float eps = std::numeric_limits<float>::epsilon() * 0.5f;
  return (n * eps) / (1.0f - n * eps);
}

// ---------------------------------------------------------------------------
// Inline definitions of the hot tests.
// ---------------------------------------------------------------------------

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

bool BoxTester::intersect(const Aabb& box, float tmin, float tmax, float* t_enter, float* t_exit) const {
  constexpr float widen = 1.0f + 2.0f * gamma_bound(3);
  // Near and far slab by the sign of the direction, not by comparing the distances: with
  // -0.0 one distance may be NaN and a comparison would pick the wrong side. The max/min
  // below are written so a NaN (0 * inf: origin on a slab plane, zero direction) leaves the
  // interval unchanged instead of poisoning it. No early exit: straight-line code is faster.
  const float* lo = &box.min.x;
  const float* hi = &box.max.x;
  for (int axis = 0; axis < 3; ++axis) {
    const float t_near = ((negative[axis] ? hi : lo)[axis] - org[axis]) * inv_dir[axis];
    const float t_far = ((negative[axis] ? lo : hi)[axis] - org[axis]) * inv_dir[axis] * widen;
    tmin = t_near > tmin ? t_near : tmin;
    tmax = t_far < tmax ? t_far : tmax;
  }
  *t_enter = tmin;
  *t_exit = tmax;
  return tmin <= tmax;
}


}  // namespace accel
