// App, part 4: the script commands (script.h lists them). Builds, heat maps, comparisons
// and sweeps run synchronously in script mode, so every command sees the result of the
// previous one; screenshots go through the ScriptHost (main.cpp).
#include <cinttypes>
#include <cstdio>

#include "app.h"
#include "registry.h"

namespace viz {

std::optional<accel::Error> App::execute(const ScriptCommand& c, ScriptHost& host) {
  auto need_trace = [&]() -> std::optional<accel::Error> {
    if (!ray_.active) return accel::make_error("no debug ray yet (use ray-at-pixel or ray first)");
    if (ray_.player.empty()) return accel::make_error("the ray has no recorded trace (no structure built)");
    return std::nullopt;
  };
  auto need_structure = [&]() -> std::optional<accel::Error> {
    if (!build_error_.empty()) return accel::make_error(build_error_);
    if (!structure_matches_scene()) return accel::make_error("no structure built for this scene");
    return std::nullopt;
  };
  // The camera as it will be drawn: framing waits for the first draw (it needs the aspect
  // ratio), but a ray shot before that must use the framed camera too.
  // One frame: lays the panels out (the 3D view's rectangle) and frames a new scene.
  auto settle_camera = [&] { host.render(layout_frames_ + 1); };

  switch (c.kind) {
    case CommandKind::Size:
      if (auto e = host.resize(c.ints[0], c.ints[1])) return e;
      framebuffer_ = host.framebuffer_size();
      layout_frames_ = 2;
      return std::nullopt;
    case CommandKind::Scene:
      if (auto e = load_scene(c.name)) return e;
      return need_structure();
    case CommandKind::Preset: {
      const Preset* p = find_preset(presets_, c.name);
      if (!p) {
        std::string names;
        for (const Preset& q : presets_) names += (names.empty() ? "" : ", ") + q.name;
        return accel::make_error("unknown preset '" + c.name + "' (valid: " + names + ")");
      }
      host.render(1);  // the current layout: the preset's centre ray goes through the 3D view's centre
      apply_preset(*p);
      if (!panel_.load_error.empty()) return accel::make_error(panel_.load_error);
      return need_structure();
    }
    case CommandKind::Structure:
      switch_structure(c.name, c.params);
      return need_structure();
    case CommandKind::Kernel: {
      accel::Kernel k;
      accel::parse_kernel(c.name, &k);
      editor_kernel_ = k;
      request_structure(request_from_editor());
      return need_structure();
    }
    case CommandKind::Camera: {
      const glm::vec3 eye(c.values[0], c.values[1], c.values[2]), target(c.values[3], c.values[4], c.values[5]);
      const float fov = c.has_fov ? c.values[6] : camera_.pinhole().fovy_deg;
      camera_.look_at(eye, target, fov, scene_->bounds());
      frame_requested_ = false;
      return std::nullopt;
    }
    case CommandKind::RayAtPixel: {
      settle_camera();
      const float x = c.values[0], y = c.values[1];
      if (x < 0.0f || y < 0.0f || x >= static_cast<float>(framebuffer_.x) || y >= static_cast<float>(framebuffer_.y)) {
        char msg[128];
        std::snprintf(msg, sizeof msg, "ray-at-pixel: (%g, %g) is outside the %dx%d window", static_cast<double>(x),
                      static_cast<double>(y), framebuffer_.x, framebuffer_.y);
        return accel::make_error(msg);
      }
      if (x < static_cast<float>(view_.x) || x >= static_cast<float>(view_.x + view_.z)) {
        char msg[160];
        std::snprintf(msg, sizeof msg, "ray-at-pixel: x = %g is under a panel; the 3D view spans x = %d..%d (or: panel off)",
                      static_cast<double>(x), view_.x, view_.x + view_.z - 1);
        return accel::make_error(msg);
      }
      // Pixel centres: "X Y" names the pixel, as a click into it does.
      shoot_ray_at_pixel(x + 0.5f, y + 0.5f, shoot_from_saved_);
      return std::nullopt;
    }
    case CommandKind::Ray: {
      accel::Ray r;
      r.org = {c.values[0], c.values[1], c.values[2]};
      r.dir = {c.values[3], c.values[4], c.values[5]};
      set_ray(r, "script");
      return std::nullopt;
    }
    case CommandKind::Step: {
      if (auto e = need_trace()) return e;
      accel::TracePlayer& p = ray_.player;
      p.pause();
      switch (c.step) {
        case StepMode::Forward: p.step_forward(static_cast<size_t>(c.ints[0])); break;
        case StepMode::Back: p.step_back(static_cast<size_t>(c.ints[0])); break;
        case StepMode::End: p.jump_to_end(); break;
        case StepMode::Hit: p.jump_to_hit(); break;
        case StepMode::Start: p.seek(0); break;
      }
      highlights_dirty_ = true;
      return std::nullopt;
    }
    case CommandKind::Show:
      switch (c.show) {
        case ShowMode::All: depth_filter_ = DepthFilter::All; break;
        case ShowMode::Leaves: depth_filter_ = DepthFilter::Leaves; break;
        case ShowMode::Depth:
          if (c.ints[0] == c.ints[1]) {
            depth_filter_ = DepthFilter::One;
            depth_one_ = c.ints[0];
          } else {
            depth_filter_ = DepthFilter::Range;
            depth_lo_ = c.ints[0];
            depth_hi_ = c.ints[1];
          }
          break;
      }
      return std::nullopt;
    case CommandKind::Heatmap:
      heatmap_on_ = c.name != "off";
      if (heatmap_on_) {
        accel::parse_cost_metric(c.name, &heatmap_metric_);
        settle_camera();
        if (auto e = need_structure()) return e;
        request_heatmap_now();
      }
      return std::nullopt;
    case CommandKind::Mesh:
      mesh_style_.mode = c.name == "solid"         ? MeshStyle::Mode::Solid
                         : c.name == "translucent" ? MeshStyle::Mode::Translucent
                         : c.name == "wireframe"   ? MeshStyle::Mode::Wireframe
                                                   : MeshStyle::Mode::Hidden;
      return std::nullopt;
    case CommandKind::EmptyCells:
      empty_cells_ = c.on;
      refresh_geometry();
      return std::nullopt;
    case CommandKind::Nodes:
      show_nodes_ = c.on;
      return std::nullopt;
    case CommandKind::Opacity:
      node_alpha_ = c.values[0];
      return std::nullopt;
    case CommandKind::Panel:
      if (c.name == "all") ui_visible_ = c.on;
      else if (c.name == "scene") panels_.main = c.on;
      else if (c.name == "ray") panels_.ray = c.on;
      else if (c.name == "steps") panels_.steps = c.on;
      else if (c.name == "code") panels_.code = c.on;
      else if (c.name == "compare") panels_.compare = c.on;
      else if (c.name == "sweep") panels_.sweep = c.on;
      else if (c.name == "legend") panels_.legend = c.on;
      if (c.on && c.name != "all") ui_visible_ = true;
      return std::nullopt;
    case CommandKind::Large:
      lecture_mode_ = c.on;
      host.render(2);  // the font switches at the next frame
      return std::nullopt;
    case CommandKind::Compare: {
      if (auto e = need_trace()) return e;
      start_compare();
      panels_.compare = true;
      for (const CompareRow& r : compare_rows_) {
        if (!r.ok) {
          std::printf("compare %s error %s\n", r.label.c_str(), r.error.c_str());
          continue;
        }
        std::printf("compare %-22s nodes %6" PRIu64 " skipped %6" PRIu64 " triangles %7" PRIu64 " steps %7zu %s\n",
                    r.label.c_str(), r.stats.nodes_visited, r.stats.nodes_culled, r.stats.prims_tested, r.steps,
                    r.hit.valid() ? ("hit " + std::to_string(r.hit.prim)).c_str() : "miss");
      }
      std::fflush(stdout);
      return std::nullopt;
    }
    case CommandKind::Sweep: {
      if (auto e = need_structure()) return e;
      const auto& info = accel::structure_registry()[static_cast<size_t>(editor_structure_)];
      int index = -1, numeric = 0;
      for (const auto& spec : info.params) {
        if (spec.type != accel::ParamSpec::Type::Int && spec.type != accel::ParamSpec::Type::Float) continue;
        if (spec.name == c.name) index = numeric;
        ++numeric;
      }
      if (index < 0) return accel::make_error("sweep: '" + c.name + "' is not a numeric parameter of " + info.name);
      sweep_param_ = index;
      sweep_lo_ = c.values[0];
      sweep_hi_ = c.values[1];
      sweep_steps_ = c.ints[0];
      settle_camera();
      start_sweep();
      if (!sweep_error_.empty()) return accel::make_error(sweep_error_);
      return std::nullopt;
    }
    case CommandKind::Screenshot:
      return host.screenshot(c.name);
    case CommandKind::Frames: {
      if (auto e = need_trace()) return e;
      constexpr size_t kMaxFrames = 5000;
      const size_t first = ray_.player.step(), last = ray_.player.size() - 1;
      if (last - first + 1 > kMaxFrames)
        return accel::make_error("frames: " + std::to_string(last - first + 1) + " steps remain; at most " +
                                 std::to_string(kMaxFrames) + " frames (step closer to the end first)");
      for (size_t s = first; s <= last; ++s) {
        ray_.player.seek(s);
        highlights_dirty_ = true;
        char path[4096];
        std::snprintf(path, sizeof path, "%s%04zu.png", c.name.c_str(), s);
        if (auto e = host.screenshot(path)) return e;
      }
      return std::nullopt;
    }
    case CommandKind::PrintHit:
      if (!ray_.active) return accel::make_error("no debug ray yet (use ray-at-pixel or ray first)");
      std::printf("%s\n", hit_line().c_str());
      std::fflush(stdout);
      return std::nullopt;
    case CommandKind::PrintStep:
      if (auto e = need_trace()) return e;
      std::printf("%s\n", step_line().c_str());
      std::fflush(stdout);
      return std::nullopt;
    case CommandKind::PrintRay: {
      if (!ray_.active) return accel::make_error("no debug ray yet (use ray-at-pixel or ray first)");
      const accel::Ray& r = ray_.ray;
      std::printf("%a %a %a %a %a %a\n", static_cast<double>(r.org.x), static_cast<double>(r.org.y),
                  static_cast<double>(r.org.z), static_cast<double>(r.dir.x), static_cast<double>(r.dir.y),
                  static_cast<double>(r.dir.z));
      std::fflush(stdout);
      return std::nullopt;
    }
    case CommandKind::PrintStats: {
      if (auto e = need_structure()) return e;
      const accel::BuildStats& s = built_->stats;
      std::printf("stats %s %s nodes %zu leaves %zu depth %d memory %zu build_ms %.3f sah %.4g\n",
                  built_->request.name.c_str(), built_->params_text.c_str(), s.nodes, s.leaves, s.max_depth,
                  s.memory_bytes, s.build_ms, s.sah_cost);
      std::fflush(stdout);
      return std::nullopt;
    }
    case CommandKind::LoadBench:
      return load_bench(c.name);
    case CommandKind::ShowChart: {
      if (!c.on) {
        chart_.open = false;
        return std::nullopt;
      }
      if (!chart_.data)
        return accel::make_error("show-chart: no bench JSON loaded (load-bench FILE or --bench-json FILE first)");
      ChartOptions options = chart_.options;
      for (const std::string& setting : c.params) set_chart_option(options, setting);  // checked by the parser
      if (options.group >= chart_.data->groups.size())
        return accel::make_error("show-chart: group=" + std::to_string(options.group + 1) + ", but " +
                                 chart_.data->path + " has " + std::to_string(chart_.data->groups.size()) +
                                 " group(s) of scene and rays");
      chart_.options = options;
      chart_.open = true;
      ui_visible_ = true;
      return std::nullopt;
    }
    case CommandKind::PrintFrameTime: {
      const double ms = host.measure_frames(c.ints[0]);
      const glm::ivec2 fb = host.framebuffer_size();
      std::printf("frame-time %.2f ms (mean of %d frames, %dx%d, %zu triangles, %zu nodes drawn, GL: %s)\n", ms,
                  c.ints[0], fb.x, fb.y, scene_->triangle_count(), show_nodes_ ? drawn_nodes_ : size_t{0},
                  host.gl_renderer().c_str());
      std::fflush(stdout);
      return std::nullopt;
    }
  }
  return std::nullopt;
}

}  // namespace viz
