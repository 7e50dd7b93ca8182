#include "planar_geometry.h"

#include <algorithm>
#include <cmath>

namespace accel {
namespace {

/// What the test needs of one vertex, computed from that vertex and the ray alone.
struct VertexSide {
  double side;   // d x (p - o): > 0 left of the ray's line, < 0 right, 0 on it
  double along;  // d . (p - o): the parameter of p's projection, times |d|^2
};

/// True when vertex a comes before b in the order that fixes each edge's orientation.
bool before(const Vec3& a, const Vec3& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

}  // namespace

PlanarRayTester::PlanarRayTester(const Ray& ray)
    : ox_(ray.org.x), oy_(ray.org.y), dx_(ray.dir.x), dy_(ray.dir.y),
      length2_(double(ray.dir.x) * ray.dir.x + double(ray.dir.y) * ray.dir.y), tmin_(ray.tmin) {}

bool PlanarRayTester::intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, double tmax, double* t, double* u,
                                double* v) const {
  // The ray's line meets the closed triangle in a chord (possibly one point) whose ends lie
  // on the triangle's boundary: at vertices on the line and where an edge's ends lie on
  // opposite sides of it. The ray hits where that chord overlaps [tmin, tmax].
  const Vec3* p[3] = {&p0, &p1, &p2};
  VertexSide s[3];
  for (int k = 0; k < 3; ++k) {
    const double x = double(p[k]->x) - ox_, y = double(p[k]->y) - oy_;
    s[k] = {dx_ * y - dy_ * x, dx_ * x + dy_ * y};
  }
  double lo = kInf, hi = -kInf;
  auto chord_end = [&](double along) {
    lo = std::min(lo, along);
    hi = std::max(hi, along);
  };
  for (int k = 0; k < 3; ++k) {
    if (s[k].side == 0.0) chord_end(s[k].along);
    int a = k, b = (k + 1) % 3;
    if (!((s[a].side < 0.0 && s[b].side > 0.0) || (s[a].side > 0.0 && s[b].side < 0.0))) continue;
    if (before(*p[b], *p[a])) std::swap(a, b);  // the same orientation in both triangles of an edge
    const double lambda = s[a].side / (s[a].side - s[b].side);
    chord_end(s[a].along + lambda * (s[b].along - s[a].along));
  }
  if (lo > hi) return false;  // every vertex strictly on one side: the line misses
  const double enter = lo / length2_, leave = hi / length2_;
  if (enter > tmax || leave < tmin_ || tmin_ > tmax) return false;
  *t = std::max(enter, tmin_);
  // Barycentrics of the hit point from the areas it spans with the edges.
  const double hx = ox_ + *t * dx_, hy = oy_ + *t * dy_;
  const double ex = double(p1.x) - p0.x, ey = double(p1.y) - p0.y;
  const double fx = double(p2.x) - p0.x, fy = double(p2.y) - p0.y;
  const double gx = hx - p0.x, gy = hy - p0.y;
  const double area = ex * fy - ey * fx;
  *u = (gx * fy - gy * fx) / area;
  *v = (ex * gy - ey * gx) / area;
  return true;
}

bool is_planar_ray(const Ray& ray) {
  return ray.org.z == 0.0f && ray.dir.z == 0.0f && (ray.dir.x != 0.0f || ray.dir.y != 0.0f);
}

}  // namespace accel
