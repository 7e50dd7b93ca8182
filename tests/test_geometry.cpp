// Ray/triangle and ray/box tests against the hit rule of docs/hits.md.
#include <array>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "geometry.h"
#include "random.h"

namespace accel {
namespace {

const Vec3 kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);  // unit right triangle in z = 0

Ray down_at(float x, float y) {
  Ray r;
  r.org = Vec3(x, y, 1.0f);
  r.dir = Vec3(0, 0, -1);
  return r;
}

bool hits(Kernel k, const Ray& r, const Vec3& a = kA, const Vec3& b = kB, const Vec3& c = kC) {
  TriangleHit h;
  return TriangleTester(r, k).intersect(a, b, c, r.tmax, &h);
}

TEST(Triangle, InteriorHitGivesTAndBarycentrics) {
  for (Kernel k : {Kernel::Watertight, Kernel::Moller, Kernel::Double}) {
    TriangleHit h;
    ASSERT_TRUE(TriangleTester(down_at(0.25f, 0.5f), k).intersect(kA, kB, kC, kInf, &h));
    EXPECT_FLOAT_EQ(h.t, 1.0f);
    EXPECT_FLOAT_EQ(h.u, 0.25f);  // weight of kB
    EXPECT_FLOAT_EQ(h.v, 0.5f);   // weight of kC
  }
}

TEST(Triangle, EdgesAndVerticesAreHit) {
  // docs/hits.md: the triangle is closed.
  for (Kernel k : {Kernel::Watertight, Kernel::Double}) {
    EXPECT_TRUE(hits(k, down_at(0.0f, 0.0f))) << kernel_name(k);   // vertex
    EXPECT_TRUE(hits(k, down_at(1.0f, 0.0f))) << kernel_name(k);   // vertex
    EXPECT_TRUE(hits(k, down_at(0.5f, 0.0f))) << kernel_name(k);   // edge
    EXPECT_TRUE(hits(k, down_at(0.5f, 0.5f))) << kernel_name(k);   // hypotenuse
    EXPECT_FALSE(hits(k, down_at(0.5f, -1e-6f))) << kernel_name(k);
  }
}

TEST(Triangle, BothWindingsAreHit) {
  EXPECT_TRUE(hits(Kernel::Watertight, down_at(0.2f, 0.2f), kA, kC, kB));
  Ray up = down_at(0.2f, 0.2f);
  up.org.z = -1.0f;
  up.dir = Vec3(0, 0, 1);
  EXPECT_TRUE(hits(Kernel::Watertight, up));
}

TEST(Triangle, TminTmaxAreInclusive) {
  for (Kernel k : {Kernel::Watertight, Kernel::Moller, Kernel::Double}) {
    Ray r = down_at(0.2f, 0.2f);
    r.tmax = 1.0f;
    EXPECT_TRUE(hits(k, r)) << kernel_name(k);
    r.tmax = 0.999f;
    EXPECT_FALSE(hits(k, r)) << kernel_name(k);
    r.tmax = kInf;
    r.tmin = 1.0f;
    EXPECT_TRUE(hits(k, r)) << kernel_name(k);
    r.tmin = 1.001f;
    EXPECT_FALSE(hits(k, r)) << kernel_name(k);
  }
}

TEST(Triangle, RayInPlaneOrParallelIsNeverAHit) {
  Ray r;
  r.org = Vec3(-1.0f, 0.25f, 0.0f);  // travels inside z = 0 across the triangle
  r.dir = Vec3(1, 0, 0);
  for (Kernel k : {Kernel::Watertight, Kernel::Moller, Kernel::Double}) EXPECT_FALSE(hits(k, r)) << kernel_name(k);
  r.org.z = 0.5f;  // parallel above it
  for (Kernel k : {Kernel::Watertight, Kernel::Moller, Kernel::Double}) EXPECT_FALSE(hits(k, r)) << kernel_name(k);
}

TEST(Triangle, DegenerateDetection) {
  EXPECT_TRUE(is_degenerate(kA, kA, kB));
  EXPECT_TRUE(is_degenerate(kA, kB, Vec3(2, 0, 0)));  // collinear
  EXPECT_FALSE(is_degenerate(kA, kB, kC));
  EXPECT_FALSE(is_degenerate(kA, kB, Vec3(2, 1e-30f, 0)));  // tiny but not zero area
}

TEST(Triangle, WatertightAgreesWithDoubleOnRandomTriangles) {
  // Away from edges the float result equals the reference; count disagreements overall.
  Rng rng(7);
  int disagreements = 0;
  for (int i = 0; i < 200000; ++i) {
    const Vec3 a(rng.uniform(), rng.uniform(), rng.uniform());
    const Vec3 b(rng.uniform(), rng.uniform(), rng.uniform());
    const Vec3 c(rng.uniform(), rng.uniform(), rng.uniform());
    Ray r;
    r.org = Vec3(rng.uniform(-1, 2), rng.uniform(-1, 2), rng.uniform(-1, 2));
    r.dir = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    TriangleHit h;
    const bool f = TriangleTester(r, Kernel::Watertight).intersect(a, b, c, kInf, &h);
    double t, u, v;
    const bool d = intersect_triangle_double(r, a, b, c, INFINITY, &t, &u, &v);
    if (f != d) {
      ++disagreements;
      continue;
    }
    if (f) {
      EXPECT_NEAR(h.t, t, 1e-4 * std::max(1.0, std::abs(t)));
    }
  }
  // Where float rounding could flip the answer the kernel asks the double test, so none differ.
  EXPECT_EQ(disagreements, 0);
}

TEST(Triangle, WatertightHasNoCracksBetweenNeighbours) {
  // Two triangles sharing the diagonal of a square: every ray through the diagonal hits one.
  const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(1, 1, 0), p3(0, 1, 0);
  Rng rng(3);
  for (int i = 0; i < 20000; ++i) {
    const float s = rng.uniform();
    Ray r;
    r.org = Vec3(s, s, 0.0f) + Vec3(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(1, 5));
    r.dir = Vec3(s, s, 0.0f) - r.org;
    TriangleTester t(r, Kernel::Watertight);
    TriangleHit h;
    const bool any = t.intersect(p0, p1, p2, kInf, &h) || t.intersect(p0, p2, p3, kInf, &h);
    ASSERT_TRUE(any) << "crack at s=" << s;
  }
}

/// Fills lane `lane` of `block` with triangle (a, b, c).
void set_lane(TriangleBlock* block, int lane, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 p[3] = {a, b, c};
  for (int k = 0; k < 3; ++k)
    for (int axis = 0; axis < 3; ++axis) block->v[3 * k + axis][lane] = p[k][axis];
  block->prim[lane] = uint32_t(lane);
}

TEST(Triangle, FourWideTestEqualsScalarTestLaneByLane) {
  // The 4-wide kernels promise the scalar answers bit for bit (same operations, same order),
  // including the double fallback near edges, shared vertices and tmin/tmax, and unused lanes
  // never hit. Half the triangles share an edge or vertex with the ray's target point.
  Rng rng(11);
  int hits = 0;
  for (Kernel kernel : {Kernel::Watertight, Kernel::Moller, Kernel::Double}) {
    for (int i = 0; i < 20000; ++i) {
      Ray r;
      r.org = Vec3(rng.uniform(-1, 2), rng.uniform(-1, 2), rng.uniform(-1, 2));
      const Vec3 target(rng.uniform(), rng.uniform(), rng.uniform());
      r.dir = target - r.org;
      if (i % 3 == 0) r.dir[i % 2] = 0.0f;  // axis-parallel components
      r.tmin = i % 5 == 0 ? 1.0f : 0.0f;     // origin-side hits exactly at tmin
      const float tmax = i % 7 == 0 ? 1.0f : kInf;
      TriangleBlock block{};
      Vec3 tri[4][3];
      for (int lane = 0; lane < 4; ++lane) {
        for (Vec3& p : tri[lane]) p = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
        if (lane % 2 == 0) tri[lane][lane % 3] = target;  // the ray passes through a vertex
        if (lane == 1) tri[lane][0] = 2.0f * target - tri[lane][1];  // ... or through an edge
        set_lane(&block, lane, tri[lane][0], tri[lane][1], tri[lane][2]);
      }
      const int lanes = i % 4 == 0 ? 0x7 : 0xf;
      const TriangleTester tester(r, kernel);
      alignas(16) float t[4], u[4], v[4];
      const int mask = tester.intersect4(block, lanes, tmax, t, u, v);
      for (int lane = 0; lane < 4; ++lane) {
        TriangleHit h;
        const bool scalar = ((lanes >> lane) & 1) &&
                            tester.intersect(tri[lane][0], tri[lane][1], tri[lane][2], tmax, &h);
        ASSERT_EQ(bool((mask >> lane) & 1), scalar) << kernel_name(kernel) << " ray " << i << " lane " << lane;
        if (!scalar) continue;
        ++hits;
        EXPECT_EQ(t[lane], h.t) << kernel_name(kernel) << " ray " << i << " lane " << lane;
        EXPECT_EQ(u[lane], h.u);
        EXPECT_EQ(v[lane], h.v);
      }
    }
  }
  EXPECT_GT(hits, 10000);  // the comparison saw many hits, not only misses
}

TEST(Triangle, ExtremeCoordinatesGiveNoNaNHit) {
  // Found by cli.fuzz_e2e: an origin near -FLT_MAX overflows the float edge functions to
  // inf - inf = NaN, which passed every ordered comparison and came out as a hit at t = NaN.
  // Now such a test goes to the double kernel (which answers it), scalar and 4-wide alike;
  // a subnormal direction (1/dir = inf) likewise.
  Ray far;
  far.org = Vec3(-3.4e38f, 0.3f, 3.0f);
  far.dir = Vec3(1e-30f, 16777216.0f, -1.0f);
  Ray tiny = down_at(0.25f, 0.25f);
  tiny.dir = Vec3(0.0f, 0.0f, -1e-45f);
  const Vec3 big(3e38f, 0, 0);
  for (const Ray& r : {far, tiny}) {
    for (Kernel k : {Kernel::Watertight, Kernel::Moller, Kernel::Double}) {
      for (const auto& tri : {std::array<Vec3, 3>{kA, kB, kC}, std::array<Vec3, 3>{kA, big, kC}}) {
        const TriangleTester tester(r, k);
        TriangleHit h{};
        const bool scalar = tester.intersect(tri[0], tri[1], tri[2], kInf, &h);
        // The double answer, where float can hold its t (the tiny direction's t = 7e44 cannot:
        // no hit). Moller may miss here; it must only not answer NaN or inf.
        double t, u, v;
        const bool exact = intersect_triangle_double(r, tri[0], tri[1], tri[2], kInf, &t, &u, &v) &&
                           t <= double(std::numeric_limits<float>::max());
        if (k != Kernel::Moller) {
          EXPECT_EQ(scalar, exact) << kernel_name(k);
        }
        if (scalar) {
          EXPECT_TRUE(std::isfinite(h.t) && std::isfinite(h.u) && std::isfinite(h.v)) << kernel_name(k);
        }
        TriangleBlock block{};
        for (int lane = 0; lane < 4; ++lane) set_lane(&block, lane, tri[0], tri[1], tri[2]);
        alignas(16) float t4[4], u4[4], v4[4];
        const int mask = tester.intersect4(block, 0xf, kInf, t4, u4, v4);
        EXPECT_EQ(mask, scalar ? 0xf : 0) << kernel_name(k);
        for (int lane = 0; lane < 4 && mask; ++lane) EXPECT_TRUE(std::isfinite(t4[lane])) << kernel_name(k);
      }
    }
  }
}

TEST(Box, SlabTestHandlesZeroDirectionComponents) {
  Aabb box;
  box.extend(Vec3(0, 0, 0));
  box.extend(Vec3(1, 1, 1));
  for (float zero : {0.0f, -0.0f}) {
    Ray r;
    r.org = Vec3(0.0f, 0.5f, -1.0f);  // origin on the x = 0 slab plane, dir.x = +-0
    r.dir = Vec3(zero, 0.0f, 1.0f);
    float t0, t1;
    ASSERT_TRUE(BoxTester(r).intersect(box, 0.0f, kInf, &t0, &t1));
    EXPECT_FALSE(std::isnan(t0));
    EXPECT_FLOAT_EQ(t0, 1.0f);
    EXPECT_GE(t1, 2.0f);
    r.org.x = -0.1f;  // outside the slab, parallel to it: miss
    EXPECT_FALSE(BoxTester(r).intersect(box, 0.0f, kInf, &t0, &t1));
  }
}

TEST(Box, FlatBoxIsHit) {
  Aabb flat;
  flat.extend(Vec3(0, 0, 0));
  flat.extend(Vec3(1, 1, 0));
  float t0, t1;
  EXPECT_TRUE(BoxTester(down_at(0.5f, 0.5f)).intersect(flat, 0.0f, kInf, &t0, &t1));
  EXPECT_FLOAT_EQ(t0, 1.0f);
}

TEST(Sphere, EntryAndMiss) {
  BoundingSphere s{Vec3(0, 0, 0), 1.0f};
  Ray r;
  r.org = Vec3(0, 0, -5);
  r.dir = Vec3(0, 0, 1);
  float t0, t1;
  ASSERT_TRUE(intersect_sphere(r, s, 0.0f, kInf, &t0, &t1));
  EXPECT_LE(t0, 4.0f);
  EXPECT_NEAR(t0, 4.0f, 1e-5);
  EXPECT_GE(t1, 6.0f);
  r.org.x = 1.01f;
  EXPECT_FALSE(intersect_sphere(r, s, 0.0f, kInf, &t0, &t1));
}

}  // namespace
}  // namespace accel
