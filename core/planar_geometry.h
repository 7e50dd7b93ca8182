#pragma once
// The blackboard's geometry (issue #32): 2D scenes are triangles in the plane z = 0 and 2D
// rays run in that plane, so the 3D structures are built and traversed over them unchanged,
// and only the ray/triangle test differs: a ray in a triangle's plane never hits it in 3D
// (docs/hits.md), while in 2D it hits the triangle where it enters the closed triangle.
// This file is that test; reference_closest() (accuracy.h) runs it over a 2D scene as the
// 2D brute force, the oracle every 2D structure answers like (docs/hits.md, "2D scenes").
#include "geometry.h"

namespace accel {

/// A 2D ray prepared for 2D triangle tests: the 2D hit rule computed in double, the way
/// DoubleRayTester is the 3D rule. Watertight: the test decides from quantities of each
/// vertex alone (its side of the ray's line and its position along the ray) and of each
/// edge in one orientation, so two triangles sharing an edge agree on where a ray meets it,
/// and a ray through a shared edge or vertex hits at least one of them.
class PlanarRayTester {
 public:
  /// `ray` must be a 2D ray (is_planar_ray()); z is ignored.
  explicit PlanarRayTester(const Ray& ray);
  /// True when the closed triangle (p0, p1, p2) (x and y; it must have non-zero area) holds
  /// a point o + t*d with tmin <= t <= tmax: then *t is the smallest such t (tmin when the
  /// ray starts inside or on the triangle), *u, *v the point's barycentrics (it is
  /// (1-u-v)*p0 + u*p1 + v*p2).
  bool intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, double tmax, double* t, double* u, double* v) const;

 private:
  double ox_, oy_, dx_, dy_;
  double length2_;  // |d|^2: a point's parameter along the ray is its projection over it
  double tmin_;
};

/// A 2D ray: origin and direction with z = 0, and a direction whose x and y are not both 0.
bool is_planar_ray(const Ray& ray);

}  // namespace accel
