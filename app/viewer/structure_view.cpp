#include "structure_view.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace viz {
namespace {

std::array<glm::vec3, 8> corners(const accel::Aabb& box) {
  // Corner i has x from bit 0, y from bit 1, z from bit 2; an edge joins corners that
  // differ in exactly one bit.
  std::array<glm::vec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = {(i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y, (i & 4) ? box.max.z : box.min.z};
  return c;
}

template <class Fn>
void for_each_edge(const accel::Aabb& box, Fn&& fn) {
  const auto c = corners(box);
  for (int i = 0; i < 8; ++i)
    for (int bit = 1; bit < 8; bit <<= 1)
      if ((i & bit) == 0) fn(c[i], c[i | bit]);
}

/// The line list of unit circle `plane` (0: XY, 1: YZ, 2: ZX) in `n` segments, appended.
void append_unit_circle(std::vector<glm::vec3>& v, int plane, int n) {
  for (int i = 0; i < n; ++i) {
    const float a0 = 2.0f * std::numbers::pi_v<float> * float(i) / float(n);
    const float a1 = 2.0f * std::numbers::pi_v<float> * float(i + 1) / float(n);
    for (float a : {a0, a1}) {
      glm::vec3 p(0.0f);
      p[plane] = std::cos(a);
      p[(plane + 1) % 3] = std::sin(a);
      v.push_back(p);
    }
  }
}

/// Calls fn(a, b) for each edge of a sphere's outline (sphere_outline()); the unit shapes of
/// the two sizes drawn are made once.
template <class Fn>
void for_each_outline_edge(const glm::vec3& center, float radius, bool planar, int segments, Fn&& fn) {
  if (!(radius >= 0.0f)) return;
  glm::vec3 c = center;
  float r = radius;
  if (planar && !sphere_in_plane(center, radius, &c, &r)) return;
  static const std::vector<glm::vec3> kCircle32 = unit_circle(32), kCircle48 = unit_circle(48);
  static const std::vector<glm::vec3> kSphere32 = unit_sphere_circles(32), kSphere48 = unit_sphere_circles(48);
  std::vector<glm::vec3> other;
  const std::vector<glm::vec3>* unit = &other;
  if (segments == 32) unit = planar ? &kCircle32 : &kSphere32;
  else if (segments == 48) unit = planar ? &kCircle48 : &kSphere48;
  else other = planar ? unit_circle(segments) : unit_sphere_circles(segments);
  for (size_t i = 0; i + 1 < unit->size(); i += 2) fn(c + r * (*unit)[i], c + r * (*unit)[i + 1]);
}

NodeInstance instance_of(const accel::NodeView& v, bool planar) {
  NodeInstance n;
  n.depth = float(v.depth);
  n.leaf = v.leaf ? 1.0f : 0.0f;
  n.prims = float(v.prim_count);
  if (!v.sphere.empty()) {
    n.lo = v.sphere.center;
    float r = v.sphere.radius;
    if (planar && !sphere_in_plane(v.sphere.center, v.sphere.radius, &n.lo, &r)) r = 0.0f;  // a point: misses the plane
    n.hi = glm::vec3(r);
  } else {
    n.lo = v.box.min;
    n.hi = v.box.max;
  }
  return n;
}

}  // namespace

bool split_plane_instance(const accel::NodeView& v, NodeInstance* out) {
  if (v.split_axis < 0 || v.split_axis > 2 || v.box.empty()) return false;
  NodeInstance n;
  n.lo = v.box.min;
  n.hi = v.box.max;
  n.lo[v.split_axis] = n.hi[v.split_axis] = v.split_pos;
  n.depth = float(v.depth);
  n.leaf = 0.0f;
  n.prims = float(v.prim_count);
  n.axis = float(v.split_axis);
  *out = n;
  return true;
}

StructureGeometry structure_geometry(const accel::Structure& s, const GeometryOptions& options) {
  StructureGeometry g;
  g.planar = options.planar;
  auto add = [&g](const accel::NodeView& v) {
    if (v.id == accel::kNoNode) return;
    ++g.nodes;
    g.max_depth = std::max(g.max_depth, v.depth);
    if (v.depth != 0) g.uniform_depth = false;
    if (v.leaf) g.max_prims = std::max(g.max_prims, v.prim_count);
    if (!v.sphere.empty()) {
      g.spheres.push_back(instance_of(v, g.planar));
    } else if (!v.box.empty()) {
      g.boxes.push_back(instance_of(v, g.planar));
    }
    NodeInstance plane;
    if (split_plane_instance(v, &plane)) g.planes.push_back(plane);
  };
  const size_t total = s.build_stats().nodes;
  if (options.empty_cells) {
    // for_each_node lists non-empty grid cells only; node_view answers for every cell id.
    size_t listed = 0;
    s.for_each_node([&listed](const accel::NodeView&) { ++listed; });
    if (total > listed) {
      if (total <= options.max_empty_cells) {
        for (accel::NodeId id = 0; id < total; ++id) add(s.node_view(id));
        g.empty_cells_listed = true;
        return g;
      }
      g.empty_cells_too_many = true;
    }
  }
  s.for_each_node(add);
  return g;
}

std::vector<NodeInstance> filter_nodes(const std::vector<NodeInstance>& nodes, const NodeFilter& filter) {
  std::vector<NodeInstance> out;
  out.reserve(nodes.size());
  for (const NodeInstance& n : nodes)
    if (filter.accepts(n)) out.push_back(n);
  return out;
}

std::vector<NodeInstance> limit_drawn_nodes(std::vector<NodeInstance> nodes, size_t max_nodes) {
  if (nodes.size() <= max_nodes) return nodes;
  std::vector<size_t> per_depth;
  for (const NodeInstance& n : nodes) {
    const size_t d = static_cast<size_t>(std::max(0.0f, n.depth));
    if (d >= per_depth.size()) per_depth.resize(d + 1, 0);
    ++per_depth[d];
  }
  // Levels shallower than `cut` fit whole; of level `cut`, `share` nodes fit.
  size_t cut = 0, room = max_nodes;
  while (cut < per_depth.size() && per_depth[cut] <= room) room -= per_depth[cut++];
  const size_t at_cut = cut < per_depth.size() ? per_depth[cut] : 0;
  std::vector<NodeInstance> out;
  out.reserve(max_nodes);
  size_t seen_at_cut = 0, kept_at_cut = 0;
  for (const NodeInstance& n : nodes) {
    const size_t d = static_cast<size_t>(std::max(0.0f, n.depth));
    if (d < cut) {
      out.push_back(n);
    } else if (d == cut) {
      // Evenly spaced: keep the k-th node when it brings the kept share up to k * room / at_cut.
      ++seen_at_cut;
      if (kept_at_cut < room && kept_at_cut * at_cut < seen_at_cut * room) {
        out.push_back(n);
        ++kept_at_cut;
      }
    }
  }
  return out;
}

int depth_for_budget(const StructureGeometry& g, size_t budget) {
  std::vector<size_t> per_depth(static_cast<size_t>(std::max(g.max_depth, 0)) + 1, 0);
  for (const auto* list : {&g.boxes, &g.spheres})
    for (const NodeInstance& n : *list) ++per_depth[std::min(per_depth.size() - 1, static_cast<size_t>(n.depth))];
  size_t total = 0;
  for (size_t d = 0; d < per_depth.size(); ++d) {
    total += per_depth[d];
    if (total > budget) return static_cast<int>(d) - 1;
  }
  return g.max_depth;
}

void append_box_segments(std::vector<Segment>& out, const accel::Aabb& box, const glm::vec4& color, float width) {
  if (box.empty()) return;
  for_each_edge(box, [&](const glm::vec3& a, const glm::vec3& b) { out.push_back({a, b, color, width}); });
}

void append_box_edges(std::vector<ColorVertex>& lines, const accel::Aabb& box, const glm::vec4& color) {
  if (box.empty()) return;
  for_each_edge(box, [&](const glm::vec3& a, const glm::vec3& b) {
    lines.push_back({a, color});
    lines.push_back({b, color});
  });
}

bool sphere_in_plane(const glm::vec3& center, float radius, glm::vec3* circle_center, float* circle_radius) {
  const float h = std::abs(center.z);
  if (!(radius >= h)) return false;
  *circle_center = glm::vec3(center.x, center.y, 0.0f);
  // (r - h)(r + h): no cancellation of r^2 - h^2 when h is close to r.
  *circle_radius = h == 0.0f ? radius : std::sqrt((radius - h) * (radius + h));
  return true;
}

std::vector<glm::vec3> sphere_outline(const glm::vec3& center, float radius, bool planar, int segments) {
  std::vector<glm::vec3> out;
  for_each_outline_edge(center, radius, planar, segments, [&](const glm::vec3& a, const glm::vec3& b) {
    out.push_back(a);
    out.push_back(b);
  });
  return out;
}

void append_sphere_segments(std::vector<Segment>& out, const glm::vec3& center, float radius, const glm::vec4& color,
                            float width, bool planar, int segments) {
  for_each_outline_edge(center, radius, planar, segments,
                        [&](const glm::vec3& a, const glm::vec3& b) { out.push_back({a, b, color, width}); });
}

void append_sphere_lines(std::vector<ColorVertex>& lines, const glm::vec3& center, float radius,
                         const glm::vec4& color, bool planar) {
  for_each_outline_edge(center, radius, planar, 32, [&](const glm::vec3& a, const glm::vec3& b) {
    lines.push_back({a, color});
    lines.push_back({b, color});
  });
}

void append_node_segments(std::vector<Segment>& out, const accel::NodeView& v, const glm::vec4& color, float width,
                          bool planar) {
  if (!v.sphere.empty()) {
    append_sphere_segments(out, v.sphere.center, v.sphere.radius, color, width, planar);
  } else {
    append_box_segments(out, v.box, color, width);
  }
}

void append_node_lines(std::vector<ColorVertex>& lines, const accel::NodeView& v, const glm::vec4& color,
                       bool planar) {
  if (!v.sphere.empty()) {
    append_sphere_lines(lines, v.sphere.center, v.sphere.radius, color, planar);
  } else {
    append_box_edges(lines, v.box, color);
  }
}

std::vector<glm::vec3> unit_cube_edges() {
  std::vector<glm::vec3> v;
  accel::Aabb unit;
  unit.min = glm::vec3(0.0f);
  unit.max = glm::vec3(1.0f);
  for_each_edge(unit, [&](const glm::vec3& a, const glm::vec3& b) {
    v.push_back(a);
    v.push_back(b);
  });
  return v;
}

std::vector<glm::vec3> unit_sphere_circles(int segments) {
  std::vector<glm::vec3> v;
  for (int plane = 0; plane < 3; ++plane) append_unit_circle(v, plane, std::max(segments, 8));
  return v;
}

std::vector<glm::vec3> unit_circle(int segments) {
  std::vector<glm::vec3> v;
  append_unit_circle(v, 0, std::max(segments, 8));
  return v;
}

std::vector<glm::vec3> unit_square_triangles() {
  return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
}


}  // namespace viz
