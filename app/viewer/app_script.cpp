// App, part 3: the script commands (script.h lists them), one case each, calling the
// tools' methods. Builds, heat maps, comparisons and sweeps run synchronously in script
// mode, so every command sees the result of the previous one; screenshots go through the
// ScriptHost (main.cpp).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>

#include "app.h"
#include "batch.h"
#include "ray_gen.h"
#include "registry.h"
#include "tools/traversal_numbers.h"

namespace viz {
namespace {

void print_line(const std::string& line) {
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

}  // namespace

void App::walk_recorded(size_t from, size_t to, const std::function<void(size_t)>& seek, ScriptHost& host) {
  // A recording holds one frame per step: walk there one step and one frame at a time.
  while (from != to) {
    from = from < to ? from + 1 : from - 1;
    seek(from);
    host.render(1);
  }
}

accel::Status App::execute(const ScriptCommand& c, ScriptHost& host) {
  // The camera as it will be drawn: framing waits for the first draw (it needs the aspect
  // ratio), but a ray shot before that must use the framed camera too.
  // One frame: lays the panels out (the 3D view's rectangle) and frames a new scene.
  auto settle_camera = [&] { host.render(layout_frames_ + 1); };

  switch (c.kind) {
    case CommandKind::Size:
      if (auto st = host.resize(c.ints[0], c.ints[1]); !st) return st;
      framebuffer_ = host.framebuffer_size();
      layout_frames_ = 2;
      return {};
    case CommandKind::Scene:
      if (auto st = load_scene(c.name); !st) return st;
      return loaded();
    case CommandKind::Preset: {
      const Preset* p = find_preset(session_.presets(), c.name);
      if (!p) {
        std::string names;
        for (const Preset& q : session_.presets()) names += (names.empty() ? "" : ", ") + q.name;
        return accel::make_error("unknown preset '" + c.name + "' (valid: " + names + ")");
      }
      host.render(1);  // the current layout: the preset's centre ray goes through the 3D view's centre
      if (auto st = apply_preset(*p); !st) return st;
      return loaded();
    }
    case CommandKind::Structure:
      session_.switch_structure(c.name, c.params);
      sync_session();
      return loaded();
    case CommandKind::Kernel: {
      accel::Kernel k = accel::Kernel::Watertight;
      accel::parse_kernel(c.name, &k);  // checked by the parser
      session_.set_kernel(k);
      sync_session();
      return loaded();
    }
    case CommandKind::Camera: {
      const glm::vec3 eye(c.values[0], c.values[1], c.values[2]), target(c.values[3], c.values[4], c.values[5]);
      const float fov = c.has_fov ? c.values[6] : camera_.pinhole().fovy_deg;
      camera_.look_at(eye, target, fov, session_.scene().bounds());
      frame_requested_ = false;
      return {};
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
      shoot_at_pixel(x + 0.5f, y + 0.5f, ray_.shoot_from_saved());
      return {};
    }
    case CommandKind::Ray: {
      accel::Ray r;
      r.org = {c.values[0], c.values[1], c.values[2]};
      r.dir = {c.values[3], c.values[4], c.values[5]};
      r.tmin = c.values[6];
      r.tmax = c.values[7];
      set_ray(r, "script");
      return {};
    }
    case CommandKind::Mode:
      if (auto st = set_mode_2d(c.on); !st) return st;
      settle_camera();
      return {};
    case CommandKind::Scene2d:
      if (auto st = load_scene2d(c.name); !st) return st;
      settle_camera();
      return {};
    case CommandKind::Add2d:
      return add_triangle_2d({c.values[0], c.values[1], c.values[2], c.values[3], c.values[4], c.values[5]});
    case CommandKind::Save2d:
      return save_scene2d(c.name);
    case CommandKind::SaveState:
      return save_state(c.name);
    case CommandKind::Ray2d:
      return set_ray_2d(c.values[0], c.values[1], c.values[2], c.values[3]);
    case CommandKind::Step: {
      if (auto st = ray_.need_trace(); !st) return st;
      accel::TracePlayer& p = ray_.player();
      p.pause();
      build_.set_active(false);  // stepping the ray: back to the traversal's panels
      const size_t from = p.step();
      switch (c.step) {
        case StepMode::Forward: p.step_forward(static_cast<size_t>(c.ints[0])); break;
        case StepMode::Back: p.step_back(static_cast<size_t>(c.ints[0])); break;
        case StepMode::End: p.jump_to_end(); break;
        case StepMode::Hit: p.jump_to_hit(); break;
        case StepMode::Start: p.seek(0); break;
      }
      if (recorder_.recording()) walk_recorded(from, p.step(), [&](size_t s) { p.seek(s); }, host);
      return {};
    }
    case CommandKind::Construct:
      if (auto st = session_.need_structure(); !st) return st;
      construct();  // synchronous in script mode; in the window the playlist waits for it
      if (!synchronous_) return {};
      if (auto st = build_.need_trace(); !st) return accel::make_error("construct: " + st.error().message);
      return {};
    case CommandKind::BuildStep: {
      if (auto st = build_.need_trace(); !st) return accel::make_error("build-step: " + st.error().message);
      BuildStepPlayer& p = build_.player();
      p.pause();
      const size_t from = p.step();
      switch (c.step) {
        case StepMode::Forward: p.step_forward(static_cast<size_t>(c.ints[0])); break;
        case StepMode::Back: p.step_back(static_cast<size_t>(c.ints[0])); break;
        case StepMode::End: p.jump_to_end(); break;
        case StepMode::Start:
        case StepMode::Hit: p.seek(0); break;
      }
      build_.set_active(true);
      if (recorder_.recording()) walk_recorded(from, p.step(), [&](size_t s) { p.seek(s); }, host);
      return {};
    }
    case CommandKind::PrintBuildStep:
      if (auto st = build_.need_trace(); !st) return accel::make_error("print-build-step: " + st.error().message);
      print_line(build_.step_line());
      return {};
    case CommandKind::SahPlot:
      build_.set_sah_plot(c.on);
      return {};
    case CommandKind::Tree:
      if (tree_.on() != c.on) layout_frames_ = 2;  // the bottom dock appears or goes: lay out again
      tree_.set_on(c.on);
      if (c.on) ui_visible_ = true;
      return {};
    case CommandKind::TreeSelect:
      if (auto st = session_.need_structure(); !st) return accel::make_error("tree-select: " + st.error().message);
      tree_.update(session_.current_ptr(), ray_.ray(), build_.active() ? build_.replay() : nullptr);
      if (auto st = tree_.select(static_cast<NodeId>(c.ints[0]), c.on); !st) return st;
      ui_visible_ = true;
      return {};
    case CommandKind::Show:
      switch (c.show) {
        case ShowMode::All: nodes_.show_all(); break;
        case ShowMode::Leaves: nodes_.show_leaves(); break;
        case ShowMode::Depth: nodes_.show_depths(c.ints[0], c.ints[1]); break;
      }
      return {};
    case CommandKind::Heatmap:
      heatmap_.set_on(c.name != "off");
      if (heatmap_.on()) {
        accel::CostMetric metric = accel::CostMetric::NodesVisited;
        accel::parse_cost_metric(c.name, &metric);  // checked by the parser
        heatmap_.set_metric(metric);
        settle_camera();
        if (auto st = session_.need_structure(); !st) return st;
        heatmap_.compute_now(heatmap_view());
      }
      return {};
    case CommandKind::Mesh:
      nodes_.set_mesh_mode(c.name == "solid"         ? MeshStyle::Mode::Solid
                           : c.name == "translucent" ? MeshStyle::Mode::Translucent
                           : c.name == "wireframe"   ? MeshStyle::Mode::Wireframe
                                                     : MeshStyle::Mode::Hidden);
      return {};
    case CommandKind::EmptyCells:
      nodes_.set_empty_cells(c.on, session_.shown());
      session_.set_empty_cells(c.on);
      return {};
    case CommandKind::Nodes:
      nodes_.set_visible(c.on);
      return {};
    case CommandKind::MemoryLimit:
      session_.set_memory_limit(c.bytes);
      sync_session();
      return loaded();
    case CommandKind::Opacity:
      nodes_.set_opacity(c.values[0]);
      return {};
    case CommandKind::Panel:
      if (c.name == "all") ui_visible_ = c.on;
      else if (c.name == "scene") panels_.main = c.on;
      else if (c.name == "ray") panels_.ray = c.on;
      else if (c.name == "steps") panels_.steps = c.on;
      else if (c.name == "code") panels_.code = c.on;
      else if (c.name == "compare") compare_.set_open(c.on);
      else if (c.name == "sweep") sweep_.set_open(c.on);
      else if (c.name == "legend") panels_.legend = c.on;
      else if (c.name == "vars") panels_.vars = c.on;
      else if (c.name == "strip") panels_.strip = c.on;
      else if (c.name == "trap") trap_.set_open(c.on);
      if (c.on && c.name != "all") ui_visible_ = true;
      return {};
    case CommandKind::Large:
      lecture_mode_ = c.on;
      host.render(2);  // the font switches at the next frame
      return {};
    case CommandKind::Compare:
      if (auto st = ray_.need_trace(); !st) return st;
      start_compare();
      compare_.set_open(true);
      compare_.print_rows();
      return {};
    case CommandKind::Sweep: {
      if (auto st = session_.need_structure(); !st) return st;
      if (auto st = sweep_.configure(session_.editor_info(), c.name, c.values[0], c.values[1], c.ints[0]); !st)
        return st;
      settle_camera();
      return start_sweep();
    }
    case CommandKind::Screenshot:
      return host.screenshot(c.name);
    case CommandKind::Frames: {
      if (auto st = ray_.need_trace(); !st) return st;
      constexpr size_t kMaxFrames = 5000;
      accel::TracePlayer& p = ray_.player();
      const size_t first = p.step(), last = p.size() - 1;
      if (last - first + 1 > kMaxFrames)
        return accel::make_error("frames: " + std::to_string(last - first + 1) + " steps remain; at most " +
                                 std::to_string(kMaxFrames) + " frames (step closer to the end first)");
      for (size_t s = first; s <= last; ++s) {
        p.seek(s);
        char path[4096];
        std::snprintf(path, sizeof path, "%s%04zu.png", c.name.c_str(), s);
        if (auto st = host.screenshot(path); !st) return st;
      }
      return {};
    }
    case CommandKind::PrintVars: {
      if (auto st = ray_.need_trace(); !st) return accel::make_error("print-vars: " + st.error().message);
      const BuiltStructure* built = session_.current();
      const auto& events = ray_.ray().player.events();
      print_line(vars_line(ray_.ray().vars, events, accel::trace_highlight(events, ray_.player().step()),
                           built ? built->kind : TraversalKind::Unknown));
      return {};
    }
    case CommandKind::Trap:
      host.render(1);  // the current layout, so the scene is framed into the 3D view
      return load_trap(c.name);
    case CommandKind::PrintNaive:
      if (auto st = ray_.need_trace(); !st) return accel::make_error("print-naive: " + st.error().message);
      print_line(accel::naive_line(accel::naive_first_leaf_hit(ray_.ray().player.events())));
      return {};
    case CommandKind::Playlist:
      if (auto st = load_playlist(c.name); !st) return st;
      run_playlist(&host);
      return {};
    case CommandKind::Next:
    case CommandKind::Prev:
      if (!playlist_.loaded()) return accel::make_error("no playlist loaded (use playlist FILE first)");
      go_to_state(c.kind == CommandKind::Next ? playlist_.next_index() : playlist_.prev_index());
      run_playlist(&host);
      return {};
    case CommandKind::PrintState:
      if (!playlist_.loaded()) return accel::make_error("print-state: no playlist loaded");
      print_line(playlist_.state_line());
      return {};
    case CommandKind::Record: {
      RecordOptions o;
      o.fps = c.ints[0];
      o.ui = c.on;
      o.width = static_cast<int>(c.values[0]);
      o.height = static_cast<int>(c.values[1]);
      if (auto st = recorder_.start(c.name, o); !st) return st;
      host.render(1);  // the first frame: the animation as it stands
      if (!recorder_.recording()) return accel::make_error("record: " + recorder_.notice());
      return {};
    }
    case CommandKind::RecordStop:
      if (auto st = recorder_.stop(); !st) return st;
      print_line(recorder_.notice());  // "wrote PATH (N frames)"
      return {};
    case CommandKind::HeatmapScale: {
      HeatmapScale scale;
      scale.fixed = c.on;
      scale.lo = c.values[0];
      scale.hi = c.values[1];
      heatmap_.set_scale(scale);
      return {};
    }
    case CommandKind::HeatmapDiff: {
      std::optional<StructureRequest> other;
      if (c.on) {
        other.emplace();
        other->name = c.name;
        other->params = c.params;
      }
      heatmap_.set_difference(other);
      if (heatmap_.on()) {
        settle_camera();
        if (auto st = session_.need_structure(); !st) return st;
        heatmap_.compute_now(heatmap_view());
        if (!heatmap_.error().empty()) return accel::make_error(heatmap_.error());
      }
      return {};
    }
    case CommandKind::PrintHeatmap:
      print_line(heatmap_.summary());
      return {};
    case CommandKind::Colors: {
      ColorScheme scheme;
      parse_colormap(c.name, &scheme.map);  // checked by the parser
      scheme.cvd_safe_hits = c.on;
      set_color_scheme(scheme);
      ray_.recolor();
      return {};
    }
    case CommandKind::PrintHit:
      if (auto st = ray_.need_ray(); !st) return st;
      print_line(ray_.hit_line());
      return {};
    case CommandKind::PrintStep:
      if (auto st = ray_.need_trace(); !st) return st;
      print_line(ray_.step_line());
      return {};
    case CommandKind::PrintRay:
      if (auto st = ray_.need_ray(); !st) return st;
      print_line(ray_.ray_line());
      return {};
    case CommandKind::PrintStats: {
      if (auto st = session_.need_structure(); !st) return st;
      const BuiltStructure& b = *session_.current();
      const accel::BuildStats& s = b.stats;
      std::printf("stats %s %s nodes %zu leaves %zu depth %d memory %zu build_ms %.3f sah %.4g\n",
                  b.request.name.c_str(), b.params_text.c_str(), s.nodes, s.leaves, s.max_depth, s.memory_bytes,
                  s.build_ms, s.sah_cost);
      std::fflush(stdout);
      return {};
    }
    case CommandKind::TraceRays: {
      if (auto st = session_.need_structure(); !st) return st;
      auto rays = accel::make_rays(c.name, session_.scene());
      if (!rays) return accel::make_error("trace-rays: " + rays.error().message);
      // One thread: the same work natively and in the page, which has only one.
      const auto start = std::chrono::steady_clock::now();
      const std::vector<accel::Hit> hits = accel::trace_all(*session_.current()->structure, rays.value(), 1);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      const size_t hit_count = size_t(std::count_if(hits.begin(), hits.end(), [](const accel::Hit& h) { return h.valid(); }));
      std::printf("trace-rays %s: %zu rays, %zu hits, %.1f ms (1 thread)\n", c.name.c_str(), hits.size(), hit_count, ms);
      std::fflush(stdout);
      return {};
    }
    case CommandKind::LoadBench:
      return load_bench(c.name);
    case CommandKind::ShowChart: {
      if (!c.on) {
        chart_.open = false;
        return {};
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
      return {};
    }
    case CommandKind::PrintFrameTime: {
      const double ms = host.measure_frames(c.ints[0]);
      const glm::ivec2 fb = host.framebuffer_size();
      std::printf("frame-time %.2f ms (mean of %d frames, %dx%d, %zu triangles, %zu nodes drawn, GL: %s)\n", ms,
                  c.ints[0], fb.x, fb.y, session_.scene().triangle_count(), nodes_.drawn_nodes(),
                  host.gl_renderer().c_str());
      std::fflush(stdout);
      return {};
    }
  }
  return {};
}

}  // namespace viz
