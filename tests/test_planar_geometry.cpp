// The 2D hit rule (docs/hits.md, "2D scenes"): PlanarRayTester on hand-checked cases, its
// watertightness on shared edges and vertices, and the 2D brute force.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "accuracy.h"
#include "planar_geometry.h"

namespace accel {
namespace {

Ray ray2d(float ox, float oy, float dx, float dy, float tmin = 0.0f, float tmax = kInf) {
  Ray r;
  r.org = Vec3(ox, oy, 0.0f);
  r.dir = Vec3(dx, dy, 0.0f);
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

struct PlanarHit {
  bool hit = false;
  double t = 0, u = 0, v = 0;
};

// The triangle (0,0), (4,0), (0,4) unless given.
PlanarHit test(const Ray& ray, Vec3 a = {0, 0, 0}, Vec3 b = {4, 0, 0}, Vec3 c = {0, 4, 0}) {
  PlanarHit h;
  h.hit = PlanarRayTester(ray).intersect(a, b, c, ray.tmax, &h.t, &h.u, &h.v);
  return h;
}

TEST(PlanarHit, EntersThroughAnEdgeAtItsCrossing) {
  const PlanarHit h = test(ray2d(-2, 1, 1, 0));
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.t, 2.0);  // enters at (0, 1), on the edge from (0,0) to (0,4)
  EXPECT_EQ(h.u, 0.0);
  EXPECT_EQ(h.v, 0.25);
  // The parameter is in units of the direction: twice as long, half the t.
  EXPECT_EQ(test(ray2d(-2, 1, 2, 0)).t, 1.0);
  // From the other side it enters through the long edge x + y = 4, at (3, 1).
  const PlanarHit back = test(ray2d(6, 1, -1, 0));
  ASSERT_TRUE(back.hit);
  EXPECT_EQ(back.t, 3.0);
  EXPECT_EQ(back.u, 0.75);
  EXPECT_EQ(back.v, 0.25);
}

TEST(PlanarHit, ARayStartingInsideHitsAtTmin) {
  EXPECT_EQ(test(ray2d(1, 1, 1, 0)).t, 0.0);
  EXPECT_EQ(test(ray2d(1, 1, 1, 0, 0.5f)).t, 0.5);
  // Starting on an edge counts as inside (closed triangles).
  EXPECT_EQ(test(ray2d(0, 2, -1, 0)).t, 0.0);
  // tmin beyond the exit: the chord is behind the interval.
  EXPECT_FALSE(test(ray2d(1, 1, 1, 0, 2.5f)).hit);
}

TEST(PlanarHit, AVertexGrazedOrAnEdgeRunAlongIsAHit) {
  // y = x + 4 touches the triangle at the vertex (0, 4) only.
  const PlanarHit vertex = test(ray2d(-1, 3, 1, 1));
  ASSERT_TRUE(vertex.hit);
  EXPECT_EQ(vertex.t, 1.0);
  EXPECT_EQ(vertex.u, 0.0);
  EXPECT_EQ(vertex.v, 1.0);
  // Along the long edge x + y = 4: it meets the vertex (0, 4) first.
  const PlanarHit along = test(ray2d(-1, 5, 1, -1));
  ASSERT_TRUE(along.hit);
  EXPECT_EQ(along.t, 1.0);
  // Along the x axis from the left: the vertex (0, 0), t = 3.
  EXPECT_EQ(test(ray2d(-3, 0, 1, 0)).t, 3.0);
}

TEST(PlanarHit, MissesBesideBehindAndBeyondTmax) {
  EXPECT_FALSE(test(ray2d(-1, 3.5f, 1, 1)).hit);  // passes (0, 4.5)
  EXPECT_FALSE(test(ray2d(6, 1, 1, 0)).hit);      // pointing away
  EXPECT_FALSE(test(ray2d(-2, 1, 1, 0, 0.0f, 1.5f)).hit);
  EXPECT_TRUE(test(ray2d(-2, 1, 1, 0, 0.0f, 2.0f)).hit);  // tmax is inclusive
  EXPECT_FALSE(test(ray2d(-2, -0.5f, 1, 0)).hit);         // parallel to the bottom edge, below it
}

TEST(PlanarHit, ARayThroughASharedEdgeHitsBothItsTriangles) {
  // Two triangles sharing the edge (4,0)-(0,4), in opposite orders; rays from random origins
  // aimed at random float points of the edge's inside (the rounded direction passes within
  // float precision of the point: on the edge or just inside one of the triangles).
  const Vec3 a(0, 0, 0), b(4, 0, 0), c(0, 4, 0), d(4, 4, 0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> along(0.001f, 0.999f), far(-50.0f, 50.0f);
  int both = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 target = b + along(rng) * (c - b);
    const Vec3 origin(far(rng), far(rng), 0.0f);
    const Ray r = ray2d(origin.x, origin.y, target.x - origin.x, target.y - origin.y);
    const PlanarHit first = test(r, a, b, c), second = test(r, b, d, c);
    ASSERT_TRUE(first.hit || second.hit) << "ray " << i << " passes between the two triangles";
    both += first.hit && second.hit;
  }
  EXPECT_GT(both, 19000);  // the ray from one triangle into the other crosses the edge in both
}

TEST(PlanarHit, ARayThroughASharedVertexHitsOneOfItsFan) {
  // Eight triangles around the vertex (0,0) (a closed fan, float corners); every ray from
  // o = -10 d with integer d passes exactly through it at t = 10, so some triangle of the
  // fan is hit at t <= 10, whatever the rounding of the corners.
  std::vector<Vec3> ring;
  for (int k = 0; k < 8; ++k)
    ring.emplace_back(3.0f * std::cos(0.785398f * float(k) + 0.1f), 3.0f * std::sin(0.785398f * float(k) + 0.1f), 0.0f);
  int rays = 0;
  for (int dx = -5; dx <= 5; ++dx)
    for (int dy = -5; dy <= 5; ++dy) {
      if (dx == 0 && dy == 0) continue;
      const Ray r = ray2d(-10.0f * float(dx), -10.0f * float(dy), float(dx), float(dy));
      double closest = kInf;
      for (int k = 0; k < 8; ++k) {
        const PlanarHit h = test(r, Vec3(0.0f), ring[size_t(k)], ring[size_t((k + 1) % 8)]);
        if (h.hit) closest = std::min(closest, h.t);
      }
      EXPECT_LE(closest, 10.0) << dx << " " << dy;
      ++rays;
    }
  EXPECT_EQ(rays, 120);
}

TEST(PlanarHit, BruteForceTakesTheClosestAndTheLowerNumberOnATie) {
  // 0: far square half, 1: a degenerate (collinear) one in front of everything, 2: nearer,
  // 3: a copy of 2 (a tie).
  std::vector<Vec3> p = {{10, 0, 0}, {12, 0, 0}, {10, 2, 0}, {1, 0, 0}, {2, 1, 0}, {3, 2, 0},
                         {5, 0, 0}, {7, 0, 0}, {5, 2, 0}, {5, 0, 0}, {7, 0, 0}, {5, 2, 0}};
  std::vector<UVec3> t = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}};
  Scene scene(p, t, "tie");
  ASSERT_TRUE(scene.mark_planar());
  const ReferenceHit h = reference_closest(scene, ray2d(0, 1, 1, 0));
  EXPECT_EQ(h.prim, 2);
  EXPECT_EQ(h.t, 5.0);
  EXPECT_EQ(reference_closest(scene, ray2d(0, 1, 1, 0, 0.0f, 4.0f)).prim, -1);
  EXPECT_EQ(reference_closest(scene, ray2d(11, 0.5f, 1, 0)).prim, 0);  // starts inside 0
}

TEST(PlanarHit, PlanarRaysHaveZeroZAndAnInPlaneDirection) {
  EXPECT_TRUE(is_planar_ray(ray2d(1, 2, 0, -1)));
  EXPECT_FALSE(is_planar_ray(ray2d(1, 2, 0, 0)));
  Ray r = ray2d(1, 2, 1, 0);
  r.org.z = 1.0f;
  EXPECT_FALSE(is_planar_ray(r));
}

}  // namespace
}  // namespace accel
