#include "structures/sphere_tree.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace accel {
namespace {

/// The float sphere around the double one (c, r): the float centre moved by rounding, so
/// that shift and a relative ulp are added to the radius.
BoundingSphere round_outward(const DVec3& c, double r) {
  const Vec3 cf(c);
  const double shift = glm::length(DVec3(cf) - c);
  return {cf, float((r + shift) * (1.0 + 1e-6)) + 1e-30f};
}

/// The centre of the smallest sphere around spheres a and b.
DVec3 centre_around(const BoundingSphere& a, const BoundingSphere& b) {
  const DVec3 ca(a.center), cb(b.center);
  const double ra = a.radius, rb = b.radius;
  const DVec3 d = cb - ca;
  const double dist = glm::length(d);
  if (dist + rb <= ra) return ca;  // b inside a (also when both centres coincide)
  if (dist + ra <= rb) return cb;
  const double r = 0.5 * (dist + ra + rb);
  return ca + ((r - ra) / dist) * d;
}

}  // namespace

BoundingSphere SphereTree::fit(const Scene& scene, const uint32_t* prims, size_t n, const Aabb& box) {
  if (n == 0) return {};
  // The vertices gathered once in double: the five passes below then read one contiguous
  // array instead of chasing triangle and vertex indices each time (the same values in the
  // same order, so the same sphere). Small nodes (most of them) on the stack.
  const size_t m = 3 * n;
  constexpr size_t kOnStack = 3 * 64;
  DVec3 small[kOnStack];
  std::vector<DVec3> large(m > kOnStack ? m : 0);
  DVec3* points = m > kOnStack ? large.data() : small;
  for (size_t k = 0; k < m; ++k) points[k] = DVec3(scene.vertex(prims[k / 3], int(k % 3)));
  auto vertex = [points](size_t k) { return points[k]; };
  // Ritter: from an arbitrary point find the farthest point a, from a the farthest b; start
  // with the sphere on diameter ab and grow it to include every point outside. Squared
  // distances wherever only their order matters (a square root only for a point outside).
  auto distance2 = [](const DVec3& p, const DVec3& q) { return glm::dot(p - q, p - q); };
  const DVec3 p0 = vertex(0);
  DVec3 a = p0, b = p0;
  double best = -1.0;
  for (size_t k = 0; k < m; ++k)
    if (const double d2 = distance2(vertex(k), p0); d2 > best) { best = d2; a = vertex(k); }
  best = -1.0;
  for (size_t k = 0; k < m; ++k)
    if (const double d2 = distance2(vertex(k), a); d2 > best) { best = d2; b = vertex(k); }
  DVec3 c = 0.5 * (a + b);
  double r = 0.5 * glm::length(b - a);
  for (size_t k = 0; k < m; ++k) {
    const DVec3 p = vertex(k);
    if (const double d2 = distance2(p, c); d2 > r * r) {
      const double d = std::sqrt(d2);
      const double nr = 0.5 * (r + d);
      c += (nr - r) / d * (p - c);
      r = nr;
    }
  }
  // Tighten to the farthest vertex from the final centre (Ritter's growth overshoots).
  auto farthest = [&](const DVec3& centre) {
    double d2 = 0.0;
    for (size_t k = 0; k < m; ++k) d2 = std::max(d2, distance2(vertex(k), centre));
    return std::sqrt(d2);
  };
  double r2 = farthest(c);
  const DVec3 bc(box.center());
  const double box_r = 0.5 * glm::length(DVec3(box.extent()));
  if (box_r < r2) {
    c = bc;
    r2 = farthest(c);
  }
  return round_outward(c, r2);
}

SphereTree::Farthest SphereTree::farthest_vertex(uint32_t k, const DVec3& centre, double give_up,
                                                 const DVec3* known) const {
  // Depth-first, the child whose sphere reaches farther first; a subtree is skipped when its
  // sphere's farthest point from the centre is no farther than the best vertex so far. The
  // spheres hold their vertices (rounded outward), so nothing farther is ever skipped.
  struct Entry {
    uint32_t node;
    double reach;
  };
  Entry stack[2 * kMaxBvhDepth + 2];
  int top = 0;
  stack[top++] = {k, std::numeric_limits<double>::infinity()};
  Farthest best;
  double best2 = -1.0;  // best.distance squared: a vertex's distance needs no square root
  if (known) {
    best2 = glm::dot(*known - centre, *known - centre);
    best = {std::sqrt(best2), *known};
    if (best.distance >= give_up) return best;
  }
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.reach <= best.distance) continue;
    const Node& n = nodes_[e.node];
    if (n.leaf()) {
      for (uint32_t i = n.index; i < n.index + n.count; ++i)
        for (int v = 0; v < 3; ++v) {
          const DVec3 p(scene_->vertex(prims_[i], v));
          if (const double d2 = glm::dot(p - centre, p - centre); d2 > best2) {
            best2 = d2;
            best = {std::sqrt(d2), p};
            if (best.distance >= give_up) return best;
          }
        }
      continue;
    }
    const uint32_t children[2] = {e.node + 1, n.index};
    double reach[2];
    for (int c = 0; c < 2; ++c) {
      const BoundingSphere& s = nodes_[children[c]].volume;
      reach[c] = glm::length(DVec3(s.center) - centre) + double(s.radius);
    }
    const int first = reach[0] >= reach[1] ? 0 : 1;  // pushed last, popped first
    for (int c : {1 - first, first})
      if (reach[c] > best.distance) stack[top++] = {children[c], reach[c]};
  }
  return best;
}

BoundingSphere SphereTree::fit_inner(uint32_t k) const {
  const Node& n = nodes_[k];
  // Candidate centres, each with its exact radius (the distance to its farthest vertex):
  // the centre of the smallest sphere around the children's spheres, the box's centre, and
  // Ritter's first guess (the midpoint of a diameter found from a far vertex).
  DVec3 centre = centre_around(nodes_[k + 1].volume, nodes_[n.index].volume);
  Farthest best = farthest_vertex(k, centre);
  auto try_centre = [&](const DVec3& candidate) {
    // Only a smaller radius counts: the search gives up at the first vertex as far as the
    // best radius, and starts from the best centre's farthest vertex, the likeliest one.
    const Farthest f = farthest_vertex(k, candidate, best.distance, &best.vertex);
    if (!(f.distance < best.distance)) return false;
    best = f;
    centre = candidate;
    return true;
  };
  try_centre(DVec3(boxes_[k].center()));
  const DVec3 a = farthest_vertex(k, best.vertex).vertex;
  try_centre(0.5 * (a + farthest_vertex(k, a).vertex));
  // Then steps towards the farthest vertex (Badoiu & Clarkson 2003), a quarter of the way
  // first, the step halved whenever the radius would grow.
  constexpr int kSteps = 8;
  double step = 0.25;
  for (int i = 0; i < kSteps; ++i)
    if (!try_centre(centre + (best.vertex - centre) * step)) step *= 0.5;
  return round_outward(centre, best.distance);
}

BuildStats SphereTree::compute_stats() const {
  BuildStats s = Hierarchy::compute_stats();
  double sphere_volume = 0.0, box_volume = 0.0;
  for (size_t i = 0; i < nodes_.size(); ++i) {
    const double r = nodes_[i].volume.radius;
    sphere_volume += 4.0 / 3.0 * 3.14159265358979 * r * r * r;
    box_volume += double(boxes_[i].volume());
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", box_volume > 0.0 ? sphere_volume / box_volume : 0.0);
  s.extra.push_back({"sphere_to_box_volume", buf});
  s.extra.push_back({"fit", "bottom-up: Ritter 1990 up to 32 triangles, then the best of three centres and Badoiu-Clarkson steps, each with its farthest vertex"});
  return s;
}

}  // namespace accel
