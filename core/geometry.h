#pragma once
// Ray/triangle, ray/box and ray/sphere tests, following the hit rule of
// docs/hits.md: closed triangles (edges and vertices hit), tmin <= t <= tmax
// inclusive, never a zero-area triangle, never a triangle whose plane contains the ray.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "vec_math.h"

#include <emmintrin.h>  // SSE2: part of every x86-64 CPU

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
  Planar,      ///< 2D scenes (docs/hits.md): the 2D hit rule in double for 2D rays, the 3D one (double) for others
};
/// Every kernel of 3D scenes, the default (watertight) first: what --kernel offers. Planar is
/// not among them: build_structure() gives it to every structure over a 2D scene.
inline constexpr Kernel kAllKernels[] = {Kernel::Watertight, Kernel::Moller, Kernel::Double};
/// "watertight", "moller" or "double": what --kernel and the script command take.
std::string_view kernel_name(Kernel k);
/// Parses "watertight" / "moller" / "double"; false for anything else.
bool parse_kernel(std::string_view name, Kernel* out);
/// "watertight, moller, double": the valid names, for error messages.
std::string kernel_names_text(std::string_view separator = ", ");

/// gamma(n) = n*eps / (1 - n*eps) with eps = 2^-24 (pbrt's bound on n float roundings).
constexpr float gamma_bound(int n) {
  constexpr float eps = std::numeric_limits<float>::epsilon() * 0.5f;
  return (n * eps) / (1.0f - n * eps);
}

/// Result of one triangle test.
struct TriangleHit {
  float t, u, v;
};

/// Four triangles in structure-of-arrays form, for TriangleTester::intersect4 (the leaves of
/// the 4-wide BVH). Unused lanes are excluded by the caller's lane mask.
struct alignas(16) TriangleBlock {
  static constexpr uint32_t kNoPrim = ~0u;
  float v[9][4];     ///< rows: p0.x p0.y p0.z p1.x p1.y p1.z p2.x p2.y p2.z; columns: lanes
  uint32_t prim[4];  ///< triangle index per lane, kNoPrim when unused
  Vec3 vertex(int lane, int k) const { return {v[3 * k][lane], v[3 * k + 1][lane], v[3 * k + 2][lane]}; }
};
static_assert(sizeof(TriangleBlock) == 160);

/// A ray prepared for repeated triangle tests with one kernel (per-ray shear constants of
/// the watertight test are computed once here, not per triangle).
class TriangleTester {
 public:
  /// Inline: every query makes one, and the call and its loads were ~50 instructions a ray.
  ACCEL_FORCE_INLINE TriangleTester(const Ray& ray, Kernel kernel);
  /// True when the ray hits triangle (p0,p1,p2) at some t in [ray.tmin, tmax]; fills `out`.
  /// The caller guarantees the triangle has non-zero area (Scene marks degenerate ones).
  ACCEL_FORCE_INLINE bool intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  Kernel kernel() const { return kernel_; }
  /// intersect() on the lanes of `block` set in `lanes`, all against the same `tmax`; the
  /// watertight kernel runs on four lanes at once with SSE (same float operations as the
  /// scalar test, so the same answers), the others lane by lane. Returns the mask of hit
  /// lanes and fills t, u, v of those lanes.
  ACCEL_FORCE_INLINE int intersect4(const TriangleBlock& block, int lanes, float tmax, float* t, float* u,
                                    float* v) const;

 private:
  ACCEL_FORCE_INLINE int watertight4(const TriangleBlock& block, int lanes, float tmax, float* t, float* u,
                                     float* v) const;
  ACCEL_FORCE_INLINE int moller4(const TriangleBlock& block, int lanes, float tmax, float* t, float* u,
                                 float* v) const;
  /// Runs a scalar `test(p0, p1, p2, tmax, &hit)` on each lane set in `lanes`.
  template <class Test>
  ACCEL_FORCE_INLINE static int test_lanes(const TriangleBlock& block, int lanes, float tmax, float* t, float* u, float* v,
                        const Test& test);
  // Inline: they run in every structure's innermost loop.
  ACCEL_FORCE_INLINE bool watertight(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  inline bool moller(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  bool reference(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  /// intersect() lane by lane, for the kernels with no SIMD form (double, planar). Out of
  /// line and cold, as reference4 below, for the same reason.
  __attribute__((noinline, cold)) int scalar4(const TriangleBlock& block, int lanes, float tmax, float* t, float* u,
                                              float* v) const;
  /// reference() on the lanes of `block` set in `lanes` (the fallback of watertight4, for
  /// 0.2-0.3% of the rays). Out of line and cold: a call clobbers every vector register,
  /// and a call on the hot path made the traversal save and restore its ray constants
  /// around every leaf (9 ymm registers, ~20 instructions a leaf: bench/profile_rays.sh);
  /// on the cold path only the rays that call it pay.
  __attribute__((noinline, cold)) int reference4(const TriangleBlock& block, int lanes, float tmax, float* t,
                                                 float* u, float* v) const;
  bool planar(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax, TriangleHit* out) const;
  /// A double kernel's hit (t, u, v) as the float answer in [tmin, tmax], or none.
  bool float_answer(double t, double u, double v, float tmax, TriangleHit* out) const;

  Ray ray_;
  Kernel kernel_;
  int kx_, ky_, kz_;     // axis permutation: kz is the largest |dir| component
  float sx_, sy_, sz_;   // shear constants
  float org_kx_, org_ky_, org_kz_;  // the origin's coordinates kx, ky, kz
};

/// Double-precision watertight test of float inputs: the oracle used by tests and the
/// bench's error columns. The ray's part (axis permutation, shear, three divisions) is done
/// once at construction, since the oracle runs one ray against every triangle of a scene;
/// the per-triangle arithmetic is the same whichever way it is called.
class DoubleRayTester {
 public:
  explicit DoubleRayTester(const Ray& ray);
  /// True and t,u,v on a hit in [tmin, tmax].
  bool intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, double tmax, double* t, double* u,
                 double* v) const;

 private:
  double org_k_[3] = {};  // the origin's coordinates kx, ky, kz
  double tmin_;
  int kx_ = 0, ky_ = 1, kz_ = 2;
  double sx_ = 0, sy_ = 0, sz_ = 0;
  bool zero_dir_ = false;  // no well-defined hit
};

/// One ray against one triangle with DoubleRayTester: returns true and t,u,v on a hit in
/// [tmin, tmax].
bool intersect_triangle_double(const Ray& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                               double tmax, double* t, double* u, double* v);

/// True when the triangle has exactly zero area (cross product of its float edges, taken in
/// double, is the zero vector). docs/hits.md: such triangles are never hit.
bool is_degenerate(const Vec3& p0, const Vec3& p1, const Vec3& p2);

/// A ray prepared for slab tests: reciprocal direction with -0.0 giving -inf.
struct BoxTester {
  ACCEL_FORCE_INLINE explicit BoxTester(const Ray& ray);
  /// Clips [tmin, tmax] to the box. Conservative (Ize 2013): the far distance is widened by
  /// 1 + 2*gamma(3) so rounding never loses a hit on a box face; a zero direction component
  /// with the origin on a slab plane gives no NaN (Williams et al. 2005).
  ACCEL_FORCE_INLINE bool intersect(const Aabb& box, float tmin, float tmax, float* t_enter, float* t_exit) const;
  /// The factor of Ize's widening of far distances, 1 + 2*gamma(3).
  static constexpr float kWiden = 1.0f + 2.0f * gamma_bound(3);
  Vec3 org, inv_dir;
  /// inv_dir * kWiden (rounded): a far distance (bound - org) * inv_dir_far is widened in
  /// the same multiply. As many roundings as (bound - org) * inv_dir * kWiden, so Ize's bound
  /// holds for it the same way, and every box test (node, octree child, wide lane) saves a
  /// multiply per axis.
  Vec3 inv_dir_far;
  /// Per axis, the index in an Aabb's six floats of the bound the ray meets first (min, or
  /// max where the direction's sign bit is set, -0.0 included) and of the other one.
  uint8_t near_index[3], far_index[3];  // bytes: the kit's Ray carries a BoxTester in 128 bytes
};

/// The box whose min and max are the x, y, z lanes of two SSE registers (the builders keep
/// their bounds that way; the fourth lane is ignored).
inline Aabb aabb_from_lanes(__m128 lo, __m128 hi) {
  alignas(16) float l[4], h[4];
  _mm_store_ps(l, lo);
  _mm_store_ps(h, hi);
  Aabb b;
  b.min = Vec3(l[0], l[1], l[2]);
  b.max = Vec3(h[0], h[1], h[2]);
  return b;
}

/// Entry/exit distances of the ray through a sphere, clipped to [tmin, tmax]; conservative
/// (radius widened by a few ulps) so no enclosed hit is culled.
bool intersect_sphere(const Ray& ray, const BoundingSphere& s, float tmin, float tmax, float* t_enter,
                      float* t_exit);

// ---------------------------------------------------------------------------
// Inline definitions of the hot tests.
// ---------------------------------------------------------------------------

TriangleTester::TriangleTester(const Ray& ray, Kernel kernel) : ray_(ray), kernel_(kernel) {
  // Woop et al. 2013, section 3: permute so that kz is the dominant direction axis and the
  // winding is preserved, then shear so the ray becomes the +z axis. Written as integer
  // arithmetic on comparison results: the axes are random per ray, and the compiler turned
  // the ?: selects into two branches that mispredicted 0.9 times a ray (callgrind).
  const Vec3 a(std::fabs(ray.dir.x), std::fabs(ray.dir.y), std::fabs(ray.dir.z));  // glm::abs branches
  const int xy = int(a.x < a.y);
  const int z_wins = int(std::max(a.x, a.y) < a.z);  // max returns a.x on a tie, as xy chose
  kz_ = xy + z_wins * (2 - xy);
  // The next axes after kz, cyclically, read from two-bit fields of a constant (no static
  // table: the ISA units inline this and may not emit a shared symbol, isa_symbols_test.sh;
  // and no compare, which the compiler made a branch): kz 0 -> 1, 2; 1 -> 2, 0; 2 -> 0, 1.
  const int x = (0x09 >> (2 * kz_)) & 3, y = (0x12 >> (2 * kz_)) & 3;
  const int flip = int(component(ray.dir, kz_) < 0.0f);
  kx_ = x + flip * (y - x);
  ky_ = y + flip * (x - y);
  // The three divisions in one SSE division (each lane correctly rounded, so the values of
  // three scalar ones): a ray's set-up is a large share of a primary ray's time, and
  // divisions are the slowest of its instructions (bench/profile_rays.sh).
  alignas(16) float shear[4];
  _mm_store_ps(shear, _mm_div_ps(_mm_setr_ps(component(ray.dir, kx_), component(ray.dir, ky_), 1.0f, 1.0f),
                                 _mm_set1_ps(component(ray.dir, kz_))));
  sx_ = shear[0];
  sy_ = shear[1];
  sz_ = shear[2];
  org_kx_ = component(ray.org, kx_);
  org_ky_ = component(ray.org, ky_);
  org_kz_ = component(ray.org, kz_);
}

BoxTester::BoxTester(const Ray& ray) : org(ray.org) {
  // 1/(-0.0) = -inf and 1/(+0.0) = +inf, so the slab test needs no special case. One SSE
  // division for the three (correctly rounded per lane: the scalar divisions' values).
  const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), _mm_setr_ps(ray.dir.x, ray.dir.y, ray.dir.z, 1.0f));
  alignas(16) float lanes[4];
  _mm_store_ps(lanes, inv);
  inv_dir = Vec3(lanes[0], lanes[1], lanes[2]);
  _mm_store_ps(lanes, _mm_mul_ps(inv, _mm_set1_ps(kWiden)));
  inv_dir_far = Vec3(lanes[0], lanes[1], lanes[2]);
  const int negative = _mm_movemask_ps(inv);  // the sign bits, -inf from -0.0 included
  for (int axis = 0; axis < 3; ++axis) {
    const int neg = (negative >> axis) & 1;
    near_index[axis] = uint8_t(axis + 3 * neg);
    far_index[axis] = uint8_t(axis + 3 * (1 - neg));
  }
}

bool TriangleTester::intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax,
                               TriangleHit* out) const {
  switch (kernel_) {
    case Kernel::Watertight: return watertight(p0, p1, p2, tmax, out);
    case Kernel::Moller: return moller(p0, p1, p2, tmax, out);
    case Kernel::Double: return reference(p0, p1, p2, tmax, out);
    case Kernel::Planar: return planar(p0, p1, p2, tmax, out);
  }
  return false;
}

bool TriangleTester::watertight(const Vec3& p0, const Vec3& p1, const Vec3& p2, float tmax,
                                TriangleHit* out) const {
  // Vertices relative to the origin, permuted (kx, ky, kz): the same subtractions as p - org
  // taken per component.
  const float a_x = component(p0, kx_) - org_kx_, a_y = component(p0, ky_) - org_ky_, a_z = component(p0, kz_) - org_kz_;
  const float b_x = component(p1, kx_) - org_kx_, b_y = component(p1, ky_) - org_ky_, b_z = component(p1, kz_) - org_kz_;
  const float c_x = component(p2, kx_) - org_kx_, c_y = component(p2, ky_) - org_ky_, c_z = component(p2, kz_) - org_kz_;
  const float ax = a_x - sx_ * a_z, ay = a_y - sy_ * a_z;
  const float bx = b_x - sx_ * b_z, by = b_y - sy_ * b_z;
  const float cx = c_x - sx_ * c_z, cy = c_y - sy_ * c_z;
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
  const float m_a = std::abs(a_x) + std::abs(a_y) + (sxa + sya) * std::abs(a_z);
  const float m_b = std::abs(b_x) + std::abs(b_y) + (sxa + sya) * std::abs(b_z);
  const float m_c = std::abs(c_x) + std::abs(c_y) + (sxa + sya) * std::abs(c_z);
  const float s_a = std::abs(ax) + std::abs(ay), s_b = std::abs(bx) + std::abs(by), s_c = std::abs(cx) + std::abs(cy);
  const float bound =
      10.0f * gamma_bound(1) * (m_a * (s_b + s_c) + m_b * (s_a + s_c) + m_c * (s_a + s_b));
  // Written so a NaN or an overflow (coordinates near FLT_MAX: the products and the bound
  // are inf or NaN) is "uncertain" and goes to the double test, never through as a hit.
  const bool some_negative = u_ < -bound || v_ < -bound || w_ < -bound;
  const bool some_positive = u_ > bound || v_ > bound || w_ > bound;
  if (some_negative && some_positive) return false;  // certainly outside
  if (!(std::abs(u_) > bound && std::abs(v_) > bound && std::abs(w_) > bound))
    return reference(p0, p1, p2, tmax, out);
  const float det = u_ + v_ + w_;
  if (det == 0.0f) return false;  // ray lies in the triangle's plane (or is parallel to it)
  const float az = sz_ * a_z, bz = sz_ * b_z, cz = sz_ * c_z;
  const float t_scaled = u_ * az + v_ * bz + w_ * cz;
  const float inv_det = 1.0f / det;
  const float t = t_scaled * inv_det;
  // t carries a rounding error of a few ulps of the terms summed into it. Close to tmin or
  // tmax that error can flip the inclusive range test (origins on a surface, hits exactly
  // at tmax), so there, and only there, the double-precision test decides; a t certainly
  // outside [tmin, tmax] (behind the origin, beyond the closest hit) is rejected at once.
  const float t_err = 64.0f * gamma_bound(1) * (std::abs(u_ * az) + std::abs(v_ * bz) + std::abs(w_ * cz)) *
                      std::abs(inv_det);
  if (t + t_err < ray_.tmin || t - t_err > tmax) return false;
  // NaN (an inf scale 1/dir[kz] for a subnormal direction, inf - inf) also falls back.
  if (!(t - t_err > ray_.tmin && t + t_err < tmax)) return reference(p0, p1, p2, tmax, out);
  *out = {t, v_ * inv_det, w_ * inv_det};
  return true;
}

int TriangleTester::intersect4(const TriangleBlock& block, int lanes, float tmax, float* t, float* u,
                               float* v) const {
  if (kernel_ == Kernel::Watertight) return watertight4(block, lanes, tmax, t, u, v);
  if (kernel_ == Kernel::Moller) return moller4(block, lanes, tmax, t, u, v);
  return scalar4(block, lanes, tmax, t, u, v);
}

template <class Test>
ACCEL_FORCE_INLINE int TriangleTester::test_lanes(const TriangleBlock& block, int lanes, float tmax, float* t, float* u, float* v,
                               const Test& test) {
  int mask = 0;
  for (int lane = 0; lane < 4; ++lane) {
    TriangleHit h;
    if ((lanes >> lane) & 1 && test(block.vertex(lane, 0), block.vertex(lane, 1), block.vertex(lane, 2), tmax, &h)) {
      mask |= 1 << lane;
      t[lane] = h.t;
      u[lane] = h.u;
      v[lane] = h.v;
    }
  }
  return mask;
}

int TriangleTester::watertight4(const TriangleBlock& block, int lanes, float tmax, float* t_out, float* u_out,
                                float* v_out) const {
  // watertight() above, four lanes at a time, operation for operation in the same order.
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const auto abs = [&](__m128 x) { return _mm_and_ps(x, abs_mask); };
  const auto row = [&](int vertex, int axis) { return _mm_load_ps(block.v[3 * vertex + axis]); };
  const __m128 ox = _mm_set1_ps(org_kx_), oy = _mm_set1_ps(org_ky_), oz = _mm_set1_ps(org_kz_);
  const __m128 sx = _mm_set1_ps(sx_), sy = _mm_set1_ps(sy_), sz = _mm_set1_ps(sz_);
  // Vertex k relative to the origin, permuted (kx, ky, kz).
  __m128 rx[3], ry[3], rz[3], px[3], py[3];
  for (int k = 0; k < 3; ++k) {
    rx[k] = _mm_sub_ps(row(k, kx_), ox);
    ry[k] = _mm_sub_ps(row(k, ky_), oy);
    rz[k] = _mm_sub_ps(row(k, kz_), oz);
    px[k] = _mm_sub_ps(rx[k], _mm_mul_ps(sx, rz[k]));
    py[k] = _mm_sub_ps(ry[k], _mm_mul_ps(sy, rz[k]));
  }
  const __m128 u_ = _mm_sub_ps(_mm_mul_ps(px[2], py[1]), _mm_mul_ps(py[2], px[1]));
  const __m128 v_ = _mm_sub_ps(_mm_mul_ps(px[0], py[2]), _mm_mul_ps(py[0], px[2]));
  const __m128 w_ = _mm_sub_ps(_mm_mul_ps(px[1], py[0]), _mm_mul_ps(py[1], px[0]));
  const __m128 shear = _mm_set1_ps(std::abs(sx_) + std::abs(sy_));
  __m128 m[3], sum[3];
  for (int k = 0; k < 3; ++k) {
    m[k] = _mm_add_ps(_mm_add_ps(abs(rx[k]), abs(ry[k])), _mm_mul_ps(shear, abs(rz[k])));
    sum[k] = _mm_add_ps(abs(px[k]), abs(py[k]));
  }
  const __m128 bound = _mm_mul_ps(
      _mm_set1_ps(10.0f * gamma_bound(1)),
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(m[0], _mm_add_ps(sum[1], sum[2])), _mm_mul_ps(m[1], _mm_add_ps(sum[0], sum[2]))),
                 _mm_mul_ps(m[2], _mm_add_ps(sum[0], sum[1]))));
  const __m128 neg_bound = _mm_sub_ps(_mm_setzero_ps(), bound);
  const __m128 some_negative =
      _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u_, neg_bound), _mm_cmplt_ps(v_, neg_bound)), _mm_cmplt_ps(w_, neg_bound));
  const __m128 some_positive =
      _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u_, bound), _mm_cmpgt_ps(v_, bound)), _mm_cmpgt_ps(w_, bound));
  // Not-greater-than: true for NaN, as the scalar test's !(|u_| > bound && ...).
  const __m128 uncertain =
      _mm_or_ps(_mm_or_ps(_mm_cmpngt_ps(abs(u_), bound), _mm_cmpngt_ps(abs(v_), bound)), _mm_cmpngt_ps(abs(w_), bound));
  const int inside = lanes & ~_mm_movemask_ps(_mm_and_ps(some_negative, some_positive));
  const int edge_fallback = inside & _mm_movemask_ps(uncertain);
  int candidates = inside & ~edge_fallback;
  int fallback = edge_fallback;
  int hits = 0;
  if (candidates) {
    const __m128 det = _mm_add_ps(_mm_add_ps(u_, v_), w_);
    candidates &= ~_mm_movemask_ps(_mm_cmpeq_ps(det, _mm_setzero_ps()));
    const __m128 az = _mm_mul_ps(sz, rz[0]), bz = _mm_mul_ps(sz, rz[1]), cz = _mm_mul_ps(sz, rz[2]);
    const __m128 t_scaled = _mm_add_ps(_mm_add_ps(_mm_mul_ps(u_, az), _mm_mul_ps(v_, bz)), _mm_mul_ps(w_, cz));
    const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
    const __m128 t = _mm_mul_ps(t_scaled, inv_det);
    const __m128 t_err = _mm_mul_ps(
        _mm_mul_ps(_mm_set1_ps(64.0f * gamma_bound(1)),
                   _mm_add_ps(_mm_add_ps(abs(_mm_mul_ps(u_, az)), abs(_mm_mul_ps(v_, bz))), abs(_mm_mul_ps(w_, cz)))),
        abs(inv_det));
    const __m128 tmin4 = _mm_set1_ps(ray_.tmin), tmax4 = _mm_set1_ps(tmax);
    const __m128 lo = _mm_sub_ps(t, t_err), hi = _mm_add_ps(t, t_err);
    const int out_of_range = _mm_movemask_ps(_mm_or_ps(_mm_cmplt_ps(hi, tmin4), _mm_cmpgt_ps(lo, tmax4)));
    candidates &= ~out_of_range;
    // !(lo > tmin && hi < tmax), true for NaN lanes as in the scalar test.
    const int near_limit =
        candidates & _mm_movemask_ps(_mm_or_ps(_mm_cmpngt_ps(lo, tmin4), _mm_cmpnlt_ps(hi, tmax4)));
    fallback |= near_limit;
    hits = candidates & ~near_limit;
    if (hits) {
      _mm_storeu_ps(t_out, t);
      _mm_storeu_ps(u_out, _mm_mul_ps(v_, inv_det));
      _mm_storeu_ps(v_out, _mm_mul_ps(w_, inv_det));
    }
  }
  // Lanes too close to an edge or to tmin/tmax: the double-precision test decides (after the
  // stores above, so their answers overwrite those lanes).
  if (__builtin_expect(fallback != 0, 0)) hits |= reference4(block, fallback, tmax, t_out, u_out, v_out);
  return hits;
}

int TriangleTester::moller4(const TriangleBlock& block, int lanes, float tmax, float* t_out, float* u_out,
                            float* v_out) const {
  // moller() below, four lanes at a time, in the same operation order as glm's cross and dot.
  struct V4 {
    __m128 x, y, z;
  };
  const auto sub = [](const V4& a, const V4& b) { return V4{_mm_sub_ps(a.x, b.x), _mm_sub_ps(a.y, b.y), _mm_sub_ps(a.z, b.z)}; };
  const auto cross = [](const V4& a, const V4& b) {
    return V4{_mm_sub_ps(_mm_mul_ps(a.y, b.z), _mm_mul_ps(b.y, a.z)), _mm_sub_ps(_mm_mul_ps(a.z, b.x), _mm_mul_ps(b.z, a.x)),
              _mm_sub_ps(_mm_mul_ps(a.x, b.y), _mm_mul_ps(b.x, a.y))};
  };
  const auto dot = [](const V4& a, const V4& b) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a.x, b.x), _mm_mul_ps(a.y, b.y)), _mm_mul_ps(a.z, b.z));
  };
  const auto vertex = [&](int k) {
    return V4{_mm_load_ps(block.v[3 * k]), _mm_load_ps(block.v[3 * k + 1]), _mm_load_ps(block.v[3 * k + 2])};
  };
  const V4 dir{_mm_set1_ps(ray_.dir.x), _mm_set1_ps(ray_.dir.y), _mm_set1_ps(ray_.dir.z)};
  const V4 org{_mm_set1_ps(ray_.org.x), _mm_set1_ps(ray_.org.y), _mm_set1_ps(ray_.org.z)};
  const V4 p0 = vertex(0);
  const V4 e1 = sub(vertex(1), p0), e2 = sub(vertex(2), p0);
  const V4 pv = cross(dir, e2);
  const __m128 det = dot(e1, pv);
  const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
  const V4 tv = sub(org, p0);
  const __m128 u = _mm_mul_ps(dot(tv, pv), inv_det);
  const V4 qv = cross(tv, e1);
  const __m128 v = _mm_mul_ps(dot(dir, qv), inv_det);
  const __m128 t = _mm_mul_ps(dot(e2, qv), inv_det);
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  // The scalar test's rejections, as one mask; the ordered compares are false for NaN lanes.
  __m128 ok = _mm_cmpneq_ps(det, zero);
  ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpge_ps(u, zero), _mm_cmple_ps(u, one)));
  ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpge_ps(v, zero), _mm_cmple_ps(_mm_add_ps(u, v), one)));
  ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpge_ps(t, _mm_set1_ps(ray_.tmin)), _mm_cmple_ps(t, _mm_set1_ps(tmax))));
  ok = _mm_and_ps(ok, _mm_cmpneq_ps(t, _mm_set1_ps(kInf)));
  const int hits = lanes & _mm_movemask_ps(ok);
  if (hits) {
    _mm_storeu_ps(t_out, t);
    _mm_storeu_ps(u_out, u);
    _mm_storeu_ps(v_out, v);
  }
  return hits;
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
  if (!(u >= 0.0f && u <= 1.0f)) return false;  // NaN (coordinates near FLT_MAX) is a miss
  const Vec3 qv = glm::cross(tv, e1);
  const float v = glm::dot(ray_.dir, qv) * inv_det;
  if (!(v >= 0.0f && u + v <= 1.0f)) return false;
  const float t = glm::dot(e2, qv) * inv_det;
  if (!(t >= ray_.tmin && t <= tmax) || t == kInf) return false;  // inf: t overflowed float
  *out = {t, u, v};
  return true;
}

bool BoxTester::intersect(const Aabb& box, float tmin, float tmax, float* t_enter, float* t_exit) const {
  // Near and far slab by the sign of the direction, not by comparing the distances: with
  // -0.0 one distance may be NaN and a comparison would pick the wrong side. The max/min
  // below are written so a NaN (0 * inf: origin on a slab plane, zero direction) leaves the
  // interval unchanged instead of poisoning it. No early exit: straight-line code is faster.
  // The six bounds as one array (min then max, vec_math.h), indexed by near_index / far_index:
  // a select on the sign became a mispredicted branch once per ray at the root.
  const float* bounds = glm::value_ptr(box.min);
  for (int axis = 0; axis < 3; ++axis) {
    const float t_near = (bounds[near_index[axis]] - org[axis]) * inv_dir[axis];
    const float t_far = (bounds[far_index[axis]] - org[axis]) * inv_dir_far[axis];
    tmin = t_near > tmin ? t_near : tmin;
    tmax = t_far < tmax ? t_far : tmax;
  }
  *t_enter = tmin;
  *t_exit = tmax;
  return tmin <= tmax;
}


}  // namespace accel
