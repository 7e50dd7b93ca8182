// The construction mode's GL-free logic (tests/app/test_build_player.cpp).
#include "tools/build_playback.h"

#include <algorithm>
#include <cmath>

namespace viz {

using accel::BuildEvent;
using accel::BuildEventKind;
using accel::BuildTrace;
using accel::kNoBuildNode;

// ---------------------------------------------------------------------------------------
// Steps

std::string build_step_line(const BuildTrace& trace, size_t applied) {
  applied = std::min(applied, trace.events.size());
  std::string text = applied ? accel::describe_build_event(trace, trace.events[applied - 1]) : "nothing built yet";
  return "build step " + std::to_string(applied) + "/" + std::to_string(trace.events.size()) + ": " + text;
}

uint32_t build_event_node(const BuildEvent& e) {
  switch (e.kind) {
    case BuildEventKind::SceneBox:
    case BuildEventKind::GridResolution:
    case BuildEventKind::GridInsert:
    case BuildEventKind::Done: return kNoBuildNode;
    default: return e.node;
  }
}

// ---------------------------------------------------------------------------------------
// Cost plot

CostPlot cost_plot(const BuildTrace& trace, size_t applied) {
  CostPlot plot;
  applied = std::min(applied, trace.events.size());
  if (applied == 0) return plot;
  const BuildEvent& cur = trace.events[applied - 1];
  switch (cur.kind) {
    case BuildEventKind::Node:
    case BuildEventKind::Axis:
    case BuildEventKind::Candidates:
    case BuildEventKind::Split: break;
    default: return plot;  // other steps are not about choosing a plane
  }
  plot.node = cur.node;
  // This node's steps are contiguous (the serial, depth-first recording): walk back to its Node.
  size_t first = applied - 1;
  constexpr size_t kMaxBack = 64;
  while (first > 0 && applied - first < kMaxBack) {
    const BuildEvent& e = trace.events[first];
    if (e.node != cur.node || e.kind == BuildEventKind::Node) break;
    --first;
  }
  for (size_t k = first; k < applied; ++k) {
    const BuildEvent& e = trace.events[k];
    if (e.node != cur.node) continue;
    if (e.kind == BuildEventKind::Candidates && e.list_count > 0) {
      CostCurve c;
      c.axis = e.axis;
      const accel::SplitCandidate* cands = trace.candidates_of(e);
      for (uint32_t i = 0; i < e.list_count; ++i) {
        c.pos.push_back(cands[i].pos);
        c.cost.push_back(cands[i].cost);
        if (cands[i].cost < c.cost[c.best]) c.best = i;
      }
      plot.curves.push_back(std::move(c));
    } else if (e.kind == BuildEventKind::Split && std::isfinite(e.values[0])) {
      plot.has_leaf_cost = true;
      plot.leaf_cost = e.values[0];
    }
  }
  bool any = false;
  auto extend = [&](float v) {
    if (!std::isfinite(v)) return;
    plot.min_cost = any ? std::min(plot.min_cost, v) : v;
    plot.max_cost = any ? std::max(plot.max_cost, v) : v;
    any = true;
  };
  for (size_t i = 0; i < plot.curves.size(); ++i) {
    const CostCurve& c = plot.curves[i];
    for (float v : c.cost) extend(v);
    if (plot.best_curve < 0 || c.cost[c.best] < plot.curves[size_t(plot.best_curve)].cost[plot.curves[size_t(plot.best_curve)].best])
      plot.best_curve = static_cast<int>(i);
  }
  if (plot.has_leaf_cost) extend(plot.leaf_cost);
  return plot;
}

// ---------------------------------------------------------------------------------------
// Drawing

namespace {

const glm::vec4 kCurrentColor(1.0f, 0.85f, 0.1f, 1.0f);
const glm::vec4 kPrimColor(0.25f, 0.95f, 0.35f, 0.55f);
const glm::vec4 kPrimEdgeColor(0.25f, 0.95f, 0.35f, 0.95f);
const glm::vec4 kPlaneColor(1.0f, 0.35f, 0.85f, 0.35f);
const glm::vec4 kPlaneEdgeColor(1.0f, 0.35f, 0.85f, 1.0f);
const glm::vec4 kBboxCellColor(0.6f, 0.6f, 0.7f, 0.5f);
const glm::vec4 kKeptCellColor(0.25f, 0.85f, 1.0f, 0.95f);
const glm::vec4 kOtherColor(0.25f, 0.85f, 1.0f, 0.9f);  // the other nodes of a merge / collapse

/// A node's outline, thick: its sphere's (in 2D, `planar`, its circle in the plane) or its box.
void append_node_outline(std::vector<Segment>& out, const accel::ReplayNode& n, const glm::vec4& color, float width,
                         bool planar) {
  if (n.sphere.radius >= 0.0f) append_sphere_segments(out, n.sphere.center, n.sphere.radius, color, width, planar);
  else append_box_segments(out, n.box, color, width);
}

void append_prim(BuildView& v, const accel::Scene& scene, uint32_t prim) {
  if (prim >= scene.triangle_count()) return;
  for (int k = 0; k < 3; ++k) v.triangles.push_back({scene.vertex(prim, k), kPrimColor});
  for (int k = 0; k < 3; ++k) v.segments.push_back({scene.vertex(prim, k), scene.vertex(prim, (k + 1) % 3), kPrimEdgeColor, 1.5f});
}

accel::Aabb cell_box(const accel::ReplayGrid& g, int x, int y, int z) {
  const glm::vec3 size = (g.box.max - g.box.min) / glm::vec3(g.res[0], g.res[1], g.res[2]);
  accel::Aabb b;
  b.min = g.box.min + size * glm::vec3(x, y, z);
  b.max = b.min + size;
  return b;
}

/// A quad in the plane {p : p[axis] = pos} (axis 0..2) or {p : dot(p, dir) = pos} (axis 3) across `box`.
void append_plane(BuildView& v, const accel::Aabb& box, int axis, float pos, const glm::vec3& dir) {
  if (box.empty()) return;
  glm::vec3 q[4];
  if (axis >= 0 && axis < 3) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (glm::vec3& p : q) p = box.min;
    for (glm::vec3& p : q) p[axis] = pos;
    q[1][u] = box.max[u];
    q[2][u] = box.max[u];
    q[2][w] = box.max[w];
    q[3][w] = box.max[w];
  } else if (axis == 3 && glm::length(dir) > 0.0f) {
    const glm::vec3 n = glm::normalize(dir);
    const glm::vec3 c = 0.5f * (box.min + box.max);
    const glm::vec3 o = c + (pos - glm::dot(c, n)) * n;
    const glm::vec3 a = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
    const glm::vec3 b = glm::cross(n, a);
    const glm::vec3 ext = box.max - box.min;
    const float r = 0.5f * std::max(ext.x, std::max(ext.y, ext.z));  // about the box's size, not its diagonal
    q[0] = o - r * a - r * b;
    q[1] = o + r * a - r * b;
    q[2] = o + r * a + r * b;
    q[3] = o - r * a + r * b;
  } else {
    return;
  }
  for (int k : {0, 1, 2, 0, 2, 3}) v.triangles.push_back({q[k], kPlaneColor});
  for (int k = 0; k < 4; ++k) v.segments.push_back({q[k], q[(k + 1) % 4], kPlaneEdgeColor, 2.0f});
}

/// The PCA direction of `node`'s latest Axis event at or before `applied` (nearby steps only).
glm::vec3 pca_dir(const BuildTrace& trace, size_t applied, uint32_t node) {
  for (size_t k = applied, seen = 0; k > 0 && seen < 64; --k, ++seen) {
    const BuildEvent& e = trace.events[k - 1];
    if (e.node == node && e.kind == BuildEventKind::Axis) return e.dir;
  }
  return glm::vec3(0.0f);
}

/// The nodes built so far, coloured by depth (shallow first when there are too many).
void append_nodes_so_far(BuildView& v, const accel::BuildReplay& replay, const accel::Scene& scene) {
  const auto& nodes = replay.nodes();
  int max_depth = 1;
  for (const accel::ReplayNode& n : nodes)
    if (!n.gone) max_depth = std::max(max_depth, n.depth);
  std::vector<uint32_t> order;
  for (uint32_t s = 0; s < nodes.size(); ++s)
    if (!nodes[s].gone) order.push_back(s);
  if (order.size() > BuildView::kMaxNodes) {
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return nodes[a].depth < nodes[b].depth; });
    order.resize(BuildView::kMaxNodes);
    v.nodes_capped = true;
  }
  for (uint32_t s : order) {
    const accel::ReplayNode& n = nodes[s];
    const glm::vec3 rgb = colormap(0.15f + 0.8f * static_cast<float>(n.depth) / static_cast<float>(max_depth));
    const glm::vec4 color(rgb, n.unrecorded ? 0.35f : 0.75f);
    if (n.sphere.radius >= 0.0f) append_sphere_lines(v.lines, n.sphere.center, n.sphere.radius, color, scene.planar());
    else append_box_edges(v.lines, n.box, color);
    ++v.nodes_drawn;
  }
}

/// The grid: its box and the cells filled so far.
void append_grid_so_far(BuildView& v, const accel::ReplayGrid& g) {
  if (!g.resolved) return;
  append_box_segments(v.segments, g.box, glm::vec4(0.8f, 0.8f, 0.9f, 0.8f), 1.5f);
  size_t drawn = 0;
  for (size_t c = 0; c < g.cells.size() && drawn < BuildView::kMaxNodes; ++c) {
    if (g.cells[c].empty()) continue;
    const int x = static_cast<int>(c % size_t(g.res[0]));
    const int y = static_cast<int>((c / size_t(g.res[0])) % size_t(g.res[1]));
    const int z = static_cast<int>(c / (size_t(g.res[0]) * size_t(g.res[1])));
    const float t = std::min(1.0f, static_cast<float>(g.cells[c].size()) / 8.0f);
    append_box_edges(v.lines, cell_box(g, x, y, z), glm::vec4(colormap(0.15f + 0.8f * t), 0.5f));
    ++drawn;
  }
}

/// A GridInsert step: the cells under the triangle's bbox (thin) against the cells that
/// keep it (thick), and the triangle.
void append_grid_insert(BuildView& v, const BuildTrace& trace, const accel::ReplayGrid& g, const BuildEvent& e,
                        const accel::Scene& scene) {
  size_t drawn = 0;
  for (int z = e.lo[2]; z <= e.hi[2]; ++z)
    for (int y = e.lo[1]; y <= e.hi[1]; ++y)
      for (int x = e.lo[0]; x <= e.hi[0] && drawn < 4096; ++x, ++drawn)
        append_box_edges(v.lines, cell_box(g, x, y, z), kBboxCellColor);
  for (uint32_t i = 0; i < e.list_count && i < 4096; ++i) {
    const uint32_t c = trace.list(e)[i];
    if (!g.resolved) break;
    const int x = static_cast<int>(c % uint32_t(g.res[0]));
    const int y = static_cast<int>((c / uint32_t(g.res[0])) % uint32_t(g.res[1]));
    const int z = static_cast<int>(c / (uint32_t(g.res[0]) * uint32_t(g.res[1])));
    append_box_segments(v.segments, cell_box(g, x, y, z), kKeptCellColor, 2.5f);
  }
  append_prim(v, scene, e.prim);
}

/// A step about one node: its outline, its triangles, and what the step does to it (the
/// chosen plane, the other nodes of a merge, the triangle inserted).
void append_current_node(BuildView& v, const BuildTrace& trace, const accel::BuildReplay& replay,
                         const accel::Scene& scene, const BuildEvent& e) {
  const auto& nodes = replay.nodes();
  const size_t applied = replay.step();
  const uint32_t id = build_event_node(e);
  const uint32_t slot = id == kNoBuildNode ? kNoBuildNode : replay.slot(id);
  if (slot == kNoBuildNode || slot >= nodes.size()) return;
  const accel::ReplayNode& n = nodes[slot];
  append_node_outline(v.segments, n, kCurrentColor, 3.5f, scene.planar());
  // Its triangles (a leaf's own; an inner node's while it is being split).
  const size_t shown = std::min(n.prims.size(), BuildView::kMaxTriangles);
  for (size_t i = 0; i < shown; ++i) append_prim(v, scene, n.prims[i]);
  switch (e.kind) {
    case BuildEventKind::Candidates: {
      if (e.list_count == 0) break;
      const accel::SplitCandidate* c = trace.candidates_of(e);
      uint32_t best = 0;
      for (uint32_t i = 1; i < e.list_count; ++i)
        if (c[i].cost < c[best].cost) best = i;
      append_plane(v, n.box, e.axis, c[best].pos, e.axis == 3 ? pca_dir(trace, applied, id) : glm::vec3(0.0f));
      break;
    }
    case BuildEventKind::Split:
      append_plane(v, n.box, e.axis, e.pos, e.axis == 3 ? pca_dir(trace, applied, id) : glm::vec3(0.0f));
      break;
    case BuildEventKind::Merge:
    case BuildEventKind::Subdivide:
    case BuildEventKind::Collapse:
      for (uint32_t c : n.children)
        if (c < nodes.size() && !nodes[c].gone) append_node_outline(v.segments, nodes[c], kOtherColor, 2.0f, scene.planar());
      break;
    case BuildEventKind::InsertStep: append_prim(v, scene, e.prim); break;
    default: break;
  }
}

}  // namespace

BuildView build_view(const BuildTrace& trace, const accel::BuildReplay& replay, const accel::Scene& scene) {
  BuildView v;
  append_nodes_so_far(v, replay, scene);
  append_grid_so_far(v, replay.grid());
  const BuildEvent* e = replay.current();
  if (!e) return v;
  switch (e->kind) {
    case BuildEventKind::SceneBox:
    case BuildEventKind::GridResolution: append_box_segments(v.segments, e->box, kCurrentColor, 3.0f); break;
    case BuildEventKind::GridInsert: append_grid_insert(v, trace, replay.grid(), *e, scene); break;
    default: append_current_node(v, trace, replay, scene, *e); break;
  }
  return v;
}

}  // namespace viz
