#pragma once
// Ray/triangle, ray/box and ray/sphere tests, following the hit rule of
// ../shared/formats.md: closed triangles (edges and vertices hit), tmin <= t <= tmax
// inclusive, never a zero-area triangle, never a triangle whose plane contains the ray.
#include <cstdint>
#include <string_view>

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
  bool intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  Kernel kernel() const { return kernel_; }

 private:
  bool watertight(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  bool moller(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
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
  bool intersect(const Aabb& box, float tmin, float tmax, float* t_enter, float* t_exit) const;
  Vec3 org, inv_dir;
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

}  // namespace accel
