// The debug ray's highlights of one step: GL-free, so the tests reach them (tests/app/test_ray_debugger.cpp).
#include "tools/highlights.h"

#include <algorithm>

namespace viz {
namespace {

// Highlight colours: chosen to stay apart on a projector and from the depth colour map,
// which the highlights are drawn over (structure lines are dimmed while stepping).
const glm::vec4 kRayColor(0.95f, 0.95f, 0.97f, 0.9f);
const glm::vec4 kCurrentColor(1.0f, 0.85f, 0.1f, 1.0f);    // current node and its interval
const glm::vec4 kTrailColor(0.85f, 0.88f, 0.95f, 0.55f);   // nodes visited before
const glm::vec4 kMissedColor(0.7f, 0.55f, 1.0f, 0.6f);     // skipped: ray misses its bounds
const glm::vec4 kBeyondColor(1.0f, 0.45f, 0.15f, 0.8f);    // skipped: beyond the closest hit
const glm::vec4 kPendingColor(0.25f, 0.85f, 1.0f, 0.65f);  // on the stack / queue
const glm::vec4 kPoppedColor(1.0f, 1.0f, 1.0f, 0.95f);
// Triangle tests: the colour scheme's hit / miss pair (blue / orange unless set otherwise).
glm::vec4 test_hit_color() { return glm::vec4(hit_rgb(), 0.85f); }
glm::vec4 test_miss_color() { return glm::vec4(miss_rgb(), 0.75f); }
const glm::vec4 kClosestColor(1.0f, 0.78f, 0.05f, 0.95f);
const glm::vec4 kHitPointColor(1.0f, 0.2f, 0.9f, 1.0f);

void append_triangle(std::vector<ColorVertex>& tris, const accel::Scene& scene, int32_t prim, const glm::vec4& color) {
  if (prim < 0 || static_cast<size_t>(prim) >= scene.triangle_count()) return;
  for (int k = 0; k < 3; ++k) tris.push_back({scene.vertex(static_cast<uint32_t>(prim), k), color});
}

void append_triangle_outline(std::vector<Segment>& out, const accel::Scene& scene, int32_t prim,
                             const glm::vec4& color, float width) {
  if (prim < 0 || static_cast<size_t>(prim) >= scene.triangle_count()) return;
  const auto p = static_cast<uint32_t>(prim);
  for (int k = 0; k < 3; ++k) out.push_back({scene.vertex(p, k), scene.vertex(p, (k + 1) % 3), color, width});
}

}  // namespace

Highlights build_highlights(const DebugRay& debug, const accel::Scene& scene, const BuiltStructure* built,
                            const HighlightOptions& options) {
  Highlights out;
  if (!debug.active) return out;

  const accel::Ray& ray = debug.ray;
  const float len = ray_draw_length(ray, debug.hit, scene.bounds());
  const float t_start = std::max(ray.tmin, 0.0f);
  out.segments.push_back({ray.at(t_start), ray.at(len), kRayColor, 2.5f});
  // The hit point: a zero-length thick segment is a square of that many pixels, whatever
  // the scene's scale or the camera's distance.
  auto hit_marker = [&](const glm::vec3& p, const glm::vec4& color) {
    out.segments.push_back({p, p, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), 15.0f});
    out.segments.push_back({p, p, color, 10.0f});
  };

  const auto& events = debug.player.events();
  if (events.empty() || built == nullptr) {
    if (debug.hit.valid()) {
      append_triangle(out.triangles, scene, debug.hit.prim, kClosestColor);
      hit_marker(ray.at(debug.hit.t), kHitPointColor);
    }
    return out;
  }
  const accel::Structure& s = *built->structure;
  const bool planar = scene.planar();  // 2D: a sphere-tree node is one circle in the plane
  out.step = accel::trace_highlight(events, debug.player.step());
  const accel::TraceHighlight& h = out.step;
  out.code_line = pseudo_code_line(built->kind, events, debug.player.step(),
                                [&s](accel::NodeId id) { return s.node_view(id); });

  // The path so far (faint), the skipped nodes and the pending ones (thin lines).
  if (options.trail) {
    constexpr size_t kMaxTrail = 4000;
    const size_t first = h.visited.size() > kMaxTrail ? h.visited.size() - kMaxTrail : 0;
    for (size_t i = first; i + 1 < h.visited.size(); ++i)
      append_node_lines(out.lines, s.node_view(h.visited[i]), kTrailColor, planar);
  }
  if (options.culled) {
    for (const accel::CulledNode& c : h.culled)
      append_node_lines(out.lines, s.node_view(c.node),
                        c.reason == accel::CullReason::BeyondClosestHit ? kBeyondColor : kMissedColor, planar);
  }
  if (options.pending) {
    for (const accel::PendingNode& p : h.pending)
      append_node_lines(out.lines, s.node_view(p.node), kPendingColor, planar);
    // The node a priority queue takes next: the smallest key.
    if (built->kind == TraversalKind::HierarchyPqueue && !h.pending.empty())
      append_node_segments(out.segments, s.node_view(accel::sorted_by_key(h.pending).front().node),
                           kPendingColor, 2.5f, planar);
  }

  // The current node or cell, its split plane, and the ray's interval inside it.
  if (h.node != accel::kNoNode) {
    const accel::NodeView v = s.node_view(h.node);
    append_node_segments(out.segments, v, kCurrentColor, 3.5f, planar);
    NodeInstance plane;
    if (split_plane_instance(v, &plane)) {
      const glm::vec4 c(kCurrentColor.r, kCurrentColor.g, kCurrentColor.b, 0.28f);
      const int u = (v.split_axis + 1) % 3, w = (v.split_axis + 2) % 3;
      glm::vec3 q[4] = {plane.lo, plane.lo, plane.lo, plane.lo};
      q[1][u] = plane.hi[u];
      q[2][u] = plane.hi[u];
      q[2][w] = plane.hi[w];
      q[3][w] = plane.hi[w];
      for (int k : {0, 1, 2, 0, 2, 3}) out.triangles.push_back({q[k], c});
    }
    const float t0 = std::clamp(h.t0, t_start, len), t1 = std::clamp(h.t1, t_start, len);
    if (t1 > t0) out.segments.push_back({ray.at(t0), ray.at(t1), kCurrentColor, 8.0f});
  }

  // The node the current event is about, when it is not the current node.
  const accel::TraceEvent& e = h.event;
  if (e.node != accel::kNoNode && e.node != h.node) {
    if (e.kind == accel::TraceEventKind::Cull)
      append_node_segments(out.segments, s.node_view(e.node),
                           e.reason == accel::CullReason::BeyondClosestHit ? kBeyondColor : kMissedColor, 3.5f,
                           planar);
    else if (e.kind == accel::TraceEventKind::Push)
      append_node_segments(out.segments, s.node_view(e.node), kPendingColor, 3.5f, planar);
    else if (e.kind == accel::TraceEventKind::Pop)
      append_node_segments(out.segments, s.node_view(e.node), kPoppedColor, 3.5f, planar);
  }

  // Triangles tested in the current node (hit / miss), then the closest hit so far.
  for (const accel::TestedPrim& t : h.tested) {
    if (t.prim == h.closest_prim) continue;
    const glm::vec4 c = t.hit ? test_hit_color() : test_miss_color();
    append_triangle(out.triangles, scene, t.prim, c);
    append_triangle_outline(out.segments, scene, t.prim, c, 2.0f);
  }
  if (h.closest_prim >= 0) {
    append_triangle(out.triangles, scene, h.closest_prim, kClosestColor);
    append_triangle_outline(out.segments, scene, h.closest_prim, kClosestColor, 2.5f);
    hit_marker(ray.at(h.closest_t), kHitPointColor);
  }
  return out;
}

}  // namespace viz
