// App, part 2: the debug ray (shooting, replay after a rebuild, the highlights of the
// current step), the comparison table, the parameter sweep and the heat map jobs.
#include <algorithm>
#include <cinttypes>
#include <cstdio>

#include "app.h"
#include "registry.h"

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
const glm::vec4 kTestHitColor(0.25f, 0.95f, 0.35f, 0.85f);
const glm::vec4 kTestMissColor(1.0f, 0.25f, 0.3f, 0.75f);
const glm::vec4 kClosestColor(1.0f, 0.78f, 0.05f, 0.95f);
const glm::vec4 kHitPointColor(1.0f, 0.2f, 0.9f, 1.0f);

void append_node_lines(std::vector<ColorVertex>& lines, const accel::NodeView& v, const glm::vec4& color) {
  if (!v.sphere.empty()) {
    static const std::vector<glm::vec3> circle = unit_sphere_circles(32);
    for (const glm::vec3& p : circle) lines.push_back({v.sphere.center + v.sphere.radius * p, color});
  } else {
    append_box_edges(lines, v.box, color);
  }
}

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

// ---------------------------------------------------------------------------------------
// Shooting and replaying

void App::shoot_ray_at_pixel(float px, float py, bool from_saved_view) {
  // The core's camera model: the same ray the heat map and `accel::primary_rays` use for
  // this pixel, and the one through what is drawn there (Camera::pinhole()).
  // (px, py) are framebuffer pixels from the window's top-left; the camera images the view.
  accel::Ray ray = accel::camera_ray(camera_.pinhole(), px - static_cast<float>(view_.x),
                                     py - static_cast<float>(view_.y), view_.z, view_.w);
  std::string origin = "click";
  if (from_saved_view && saved_view_ && structure_matches_scene()) {
    // From the saved viewpoint towards the surface point under the cursor.
    const accel::Hit h = built_->structure->intersect(ray);
    if (h.valid() && ray.at(h.t) != saved_view_->eye) {
      const glm::vec3 target = ray.at(h.t);
      ray.org = saved_view_->eye;
      ray.dir = glm::normalize(target - ray.org);
      origin = "click from saved view";
    }
  }
  set_ray(ray, origin);
}

void App::set_ray(const accel::Ray& ray, const std::string& origin) {
  ray_.active = true;
  ray_.ray = ray;
  ray_.origin = origin;
  for (int i = 0; i < 3; ++i) {
    typed_ray_[i] = ray.org[i];
    typed_ray_[3 + i] = ray.dir[i];
  }
  if (structure_matches_scene()) {
    ray_.record(*built_->structure, /*keep_step=*/false);
  } else {
    ray_.hit = accel::Hit{};
    ray_.player.clear();
  }
  highlights_dirty_ = true;
  if (panels_.compare) start_compare();
}

void App::replay_ray() {
  if (!ray_.active) return;
  if (structure_matches_scene()) {
    // Same ray, new structure: the step index stays, clamped to the new trace.
    ray_.record(*built_->structure, /*keep_step=*/true);
  }
  highlights_dirty_ = true;
}

std::string App::hit_line() const {
  char text[96];
  if (ray_.hit.valid()) std::snprintf(text, sizeof text, "hit %d %.9g", ray_.hit.prim, static_cast<double>(ray_.hit.t));
  else std::snprintf(text, sizeof text, "miss");
  return text;
}

std::string App::step_line() const {
  const accel::TraceEvent* e = ray_.player.current();
  if (!e) return "no trace";
  char text[64];
  std::snprintf(text, sizeof text, "step %zu/%zu: ", ray_.player.step() + 1, ray_.player.size());
  return text + accel::describe_event(*e);
}

// ---------------------------------------------------------------------------------------
// Highlights of the current step

void App::rebuild_highlights() {
  highlights_dirty_ = false;
  highlight_step_ = ray_.player.step();
  highlights_upload_ = true;
  highlight_segments_.clear();
  highlight_triangles_.clear();
  highlight_lines_.clear();
  highlight_ = accel::TraceHighlight{};
  code_line_ = -1;
  if (!ray_.active) return;

  const accel::Ray& ray = ray_.ray;
  const float len = ray_draw_length(ray, ray_.hit, scene_->bounds());
  const float t_start = std::max(ray.tmin, 0.0f);
  highlight_segments_.push_back({ray.at(t_start), ray.at(len), kRayColor, 2.5f});
  // The hit point: a zero-length thick segment is a square of that many pixels, whatever
  // the scene's scale or the camera's distance.
  auto hit_marker = [&](const glm::vec3& p, const glm::vec4& color) {
    highlight_segments_.push_back({p, p, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), 15.0f});
    highlight_segments_.push_back({p, p, color, 10.0f});
  };

  const auto& events = ray_.player.events();
  if (events.empty() || !structure_matches_scene()) {
    if (ray_.hit.valid()) {
      append_triangle(highlight_triangles_, *scene_, ray_.hit.prim, kClosestColor);
      hit_marker(ray.at(ray_.hit.t), kHitPointColor);
    }
    return;
  }
  const accel::Structure& s = *built_->structure;
  highlight_ = accel::trace_highlight(events, ray_.player.step());
  const accel::TraceHighlight& h = highlight_;
  code_line_ = pseudo_code_line(built_->kind, events, ray_.player.step(),
                                [&s](accel::NodeId id) { return s.node_view(id); });

  // The path so far (faint), the skipped nodes and the pending ones (thin lines).
  if (show_trail_) {
    constexpr size_t kMaxTrail = 4000;
    const size_t first = h.visited.size() > kMaxTrail ? h.visited.size() - kMaxTrail : 0;
    for (size_t i = first; i + 1 < h.visited.size(); ++i)
      append_node_lines(highlight_lines_, s.node_view(h.visited[i]), kTrailColor);
  }
  if (show_culled_) {
    for (const accel::CulledNode& c : h.culled)
      append_node_lines(highlight_lines_, s.node_view(c.node),
                        c.reason == accel::CullReason::BeyondClosestHit ? kBeyondColor : kMissedColor);
  }
  if (show_pending_) {
    for (const accel::PendingNode& p : h.pending) append_node_lines(highlight_lines_, s.node_view(p.node), kPendingColor);
    // The node a priority queue takes next: the smallest key.
    if (built_->kind == TraversalKind::HierarchyPqueue && !h.pending.empty())
      append_node_segments(highlight_segments_, s.node_view(accel::sorted_by_key(h.pending).front().node),
                           kPendingColor, 2.5f);
  }

  // The current node or cell, its split plane, and the ray's interval inside it.
  if (h.node != accel::kNoNode) {
    const accel::NodeView v = s.node_view(h.node);
    append_node_segments(highlight_segments_, v, kCurrentColor, 3.5f);
    NodeInstance plane;
    if (split_plane_instance(v, &plane)) {
      const glm::vec4 c(kCurrentColor.r, kCurrentColor.g, kCurrentColor.b, 0.28f);
      const int u = (v.split_axis + 1) % 3, w = (v.split_axis + 2) % 3;
      glm::vec3 q[4] = {plane.lo, plane.lo, plane.lo, plane.lo};
      q[1][u] = plane.hi[u];
      q[2][u] = plane.hi[u];
      q[2][w] = plane.hi[w];
      q[3][w] = plane.hi[w];
      for (int k : {0, 1, 2, 0, 2, 3}) highlight_triangles_.push_back({q[k], c});
    }
    const float t0 = std::clamp(h.t0, t_start, len), t1 = std::clamp(h.t1, t_start, len);
    if (t1 > t0) highlight_segments_.push_back({ray.at(t0), ray.at(t1), kCurrentColor, 8.0f});
  }

  // The node the current event is about, when it is not the current node.
  const accel::TraceEvent& e = h.event;
  if (e.node != accel::kNoNode && e.node != h.node) {
    if (e.kind == accel::TraceEventKind::Cull)
      append_node_segments(highlight_segments_, s.node_view(e.node),
                           e.reason == accel::CullReason::BeyondClosestHit ? kBeyondColor : kMissedColor, 3.5f);
    else if (e.kind == accel::TraceEventKind::Push)
      append_node_segments(highlight_segments_, s.node_view(e.node), kPendingColor, 3.5f);
    else if (e.kind == accel::TraceEventKind::Pop)
      append_node_segments(highlight_segments_, s.node_view(e.node), kPoppedColor, 3.5f);
  }

  // Triangles tested in the current node (hit / miss), then the closest hit so far.
  for (const accel::TestedPrim& t : h.tested) {
    if (t.prim == h.closest_prim) continue;
    const glm::vec4& c = t.hit ? kTestHitColor : kTestMissColor;
    append_triangle(highlight_triangles_, *scene_, t.prim, c);
    append_triangle_outline(highlight_segments_, *scene_, t.prim, c, 2.0f);
  }
  if (h.closest_prim >= 0) {
    append_triangle(highlight_triangles_, *scene_, h.closest_prim, kClosestColor);
    append_triangle_outline(highlight_segments_, *scene_, h.closest_prim, kClosestColor, 2.5f);
    hit_marker(ray.at(h.closest_t), kHitPointColor);
  }
}

// ---------------------------------------------------------------------------------------
// Compare

void App::start_compare() {
  if (!ray_.active) return;
  compare_ray_ = ray_.ray;
  compare_progress_ = std::make_shared<std::atomic<int>>(0);
  auto scene = scene_;
  const accel::Ray ray = ray_.ray;
  const StructureRequest current = built_ ? built_->request : requested_;
  auto progress = compare_progress_;
  compare_job_.start(
      [scene, ray, current, progress](const std::atomic<bool>& cancel) {
        return compare_structures(scene, ray, current, cancel, progress.get());
      },
      synchronous_);
  if (synchronous_) poll_compare();
}

void App::poll_compare() {
  if (compare_job_.ready()) compare_rows_ = compare_job_.take();
}

// ---------------------------------------------------------------------------------------
// Sweep

void App::start_sweep() {
  const auto& info = accel::structure_registry()[static_cast<size_t>(editor_structure_)];
  std::vector<const accel::ParamSpec*> numeric;
  for (const auto& spec : info.params)
    if (spec.type == accel::ParamSpec::Type::Int || spec.type == accel::ParamSpec::Type::Float) numeric.push_back(&spec);
  if (numeric.empty()) {
    sweep_error_ = info.name + " has no numeric parameter to sweep";
    return;
  }
  sweep_param_ = std::clamp(sweep_param_, 0, static_cast<int>(numeric.size()) - 1);
  SweepRequest r;
  r.base = request_from_editor();
  r.param = numeric[static_cast<size_t>(sweep_param_)]->name;
  r.lo = sweep_lo_;
  r.hi = sweep_hi_;
  r.steps = sweep_steps_;
  r.log_scale = sweep_log_;
  r.camera = camera_.pinhole();
  sweep_request_ = r;
  sweep_error_.clear();
  sweep_progress_ = std::make_shared<SweepProgress>();
  auto progress = sweep_progress_;
  auto scene = scene_;
  sweep_job_.start([scene, r, progress](const std::atomic<bool>& cancel) { return run_sweep(scene, r, *progress, cancel); },
                   synchronous_);
  panels_.sweep = true;
  if (synchronous_) {
    auto done = sweep_job_.take();
    if (!done) sweep_error_ = done.error().message;
  }
}

// ---------------------------------------------------------------------------------------
// Heat map

App::HeatmapInputs App::heatmap_inputs() const {
  HeatmapInputs in;
  in.camera = camera_.pinhole();
  in.built = structure_matches_scene() ? built_.get() : nullptr;
  in.metric = heatmap_metric_;
  const int d = std::max(heatmap_divisor_, 1);
  in.size = glm::max(view_size() / d, glm::ivec2(1));
  return in;
}

void App::poll_heatmap(float dt) {
  if (heatmap_job_.ready()) {
    accel::CostImage image = heatmap_job_.take();
    if (image.complete) {
      heatmap_image_ = std::move(image);
      heatmap_shown_ = heatmap_running_;
      heatmap_has_image_ = true;
      heatmap_uploaded_ = false;
    }
  }
  if (!heatmap_on_) {
    heatmap_job_.cancel();
    return;
  }
  const HeatmapInputs now = heatmap_inputs();
  if (now == heatmap_last_) {
    heatmap_still_ += static_cast<double>(dt);
  } else {
    heatmap_still_ = 0.0;
    heatmap_last_ = now;
  }
  if (heatmap_job_.busy() && !(heatmap_running_ == now)) heatmap_job_.cancel();  // stale: stop early
  // Debounce: recompute once the view has been still for a moment, not while dragging.
  constexpr double kStillSeconds = 0.25;
  if (!heatmap_job_.busy() && now.built && !(heatmap_shown_ == now) && heatmap_still_ >= kStillSeconds) {
    heatmap_running_ = now;
    BuiltPtr built = built_;
    heatmap_job_.start([built, now](const std::atomic<bool>& cancel) {
      return accel::compute_cost_image(*built->structure, now.camera, now.size.x, now.size.y, now.metric, &cancel);
    });
  }
}

void App::request_heatmap_now() {
  const HeatmapInputs now = heatmap_inputs();
  if (!now.built) return;
  heatmap_job_.wait();
  heatmap_image_ = accel::compute_cost_image(*built_->structure, now.camera, now.size.x, now.size.y, now.metric);
  heatmap_shown_ = now;
  heatmap_last_ = now;
  heatmap_has_image_ = true;
  heatmap_uploaded_ = false;
}

}  // namespace viz
