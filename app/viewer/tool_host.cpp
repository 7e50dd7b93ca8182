// The wiring between tools that many of them use (tool_host.h), written once so App names
// no tool: a new ray restarts an open comparison, a preset places the camera and the ray,
// a playlist state runs its commands through App's dispatch.
#include "tool_host.h"

#include <cstdio>
#include <cstdlib>

#include <glm/glm.hpp>

#include "camera_control.h"
#include "check.h"
#include "presets.h"
#include "script.h"
#include "tools/build_player.h"
#include "tools/compare_tool.h"
#include "tools/heatmap_tool.h"
#include "tools/playlist_tool.h"
#include "tools/ray_debugger.h"
#include "tools/recorder.h"
#include "tools/structure_session.h"
#include "tools/sweep_tool.h"
#include "tools/trap_tool.h"
#include "traps.h"
#include "window_layout.h"

namespace viz {

void ToolHost::missing_tool(const std::type_info& type) {
  std::fprintf(stderr, "accelviz: internal error: no tool of type %s in App's list\n", type.name());
  std::abort();
}

StructureSession& ToolHost::session() const { return tool<StructureSession>(); }
RayDebugger& ToolHost::ray() const { return tool<RayDebugger>(); }
BuildPlayer& ToolHost::build() const { return tool<BuildPlayer>(); }

accel::Status ToolHost::loaded() const { return synchronous() ? session().need_structure() : accel::Status{}; }

void ToolHost::sync_session() {
  const SessionEvents e = session().take_events();
  if (e.scene_loaded) notify(ToolEvent::SceneLoaded);
  if (e.scene_edited) notify(ToolEvent::SceneEdited);
  if (e.structure_installed) notify(ToolEvent::StructureInstalled);
}

void ToolHost::relayout() { layout().relayout(); }
void ToolHost::show_ui() { layout().set_ui_visible(true); }

void ToolHost::settle_camera(ScriptHost& host) {
  // The camera as it will be drawn: framing waits for the first draw (it needs the aspect
  // ratio), but a ray shot before that must use the framed camera too. The frames lay the
  // panels out (the 3D view's rectangle) and frame a new scene.
  host.render(layout().frames_to_settle());
}

glm::ivec4 ToolHost::view_area() const { return layout().view(); }
glm::ivec2 ToolHost::framebuffer() const { return layout().framebuffer(); }

void ToolHost::walk_recorded(accel::PlaybackClock& clock, size_t from, ScriptHost& host) {
  if (!tool<Recorder>().recording()) return;
  // A recording holds one frame per step: walk there one step and one frame at a time.
  const size_t to = clock.step();
  while (from != to) {
    from = from < to ? from + 1 : from - 1;
    clock.seek(from);
    host.render(1);
  }
}

void ToolHost::set_ray(const accel::Ray& ray, const std::string& origin) {
  this->ray().set_ray(ray, origin, session().current());
  notify(ToolEvent::RayChanged);
}

void ToolHost::shoot_at_pixel(float px, float py, bool from_saved_view) {
  ray().shoot(camera().pinhole(), view_area(), px, py, from_saved_view, session().current());
  notify(ToolEvent::RayChanged);
}

void ToolHost::start_compare() {
  if (!ray().ray().active) return;
  tool<CompareTool>().start(session().scene_ptr(), ray().ray().ray, session().current_request(),
                            session().current_ptr(), synchronous());
}

accel::Status ToolHost::start_sweep() {
  return tool<SweepTool>().start(session().editor_info(), session().scene_ptr(), session().editor_request(),
                                 camera().pinhole(), synchronous());
}

void ToolHost::construct() { build().construct(session().scene_ptr(), session().current_request(), synchronous()); }

HeatmapView ToolHost::heatmap_view() const {
  return {camera().pinhole(), session().current_ptr(), layout().view_size()};
}

accel::Status ToolHost::apply_preset(const Preset& preset) {
  accel::Status st = session().load_preset_scene(preset);
  sync_session();
  if (!st) return st;  // the error is shown in the panel
  if (preset.has_camera) camera().look_at(preset.eye, preset.target, preset.fovy_deg, session().scene());
  ray().save_view(camera().pinhole());
  if (preset.has_ray) {
    accel::Ray ray;
    ray.org = preset.ray_origin;
    ray.dir = glm::normalize(preset.ray_target - preset.ray_origin);
    set_ray(ray, "preset " + preset.name);
  } else {
    const glm::ivec4 view = view_area();
    camera().frame_now(session().scene(), layout().view_aspect());
    shoot_at_pixel(static_cast<float>(view.x) + 0.5f * static_cast<float>(view.z),
                   static_cast<float>(view.y) + 0.5f * static_cast<float>(view.w), false);
  }
  return {};
}

accel::Status ToolHost::load_trap(const std::string& name) {
  auto found = accel::trap_demo(name);
  if (!found) return found.error();
  const accel::TrapDemo& demo = found.value();
  accel::Status st = session().load_scene(demo.scene);
  sync_session();
  if (!st) return st;
  session().switch_structure(demo.structure, demo.params);
  sync_session();
  if (auto ready = loaded(); !ready) return ready;
  tool<TrapTool>().set_demo(demo);
  set_ray(demo.ray, "trap " + demo.name);
  return {};
}

// ---------------------------------------------------------------------------------------
// The lecture playlist

namespace {

/// ScriptHost for a playlist state run in the window: the frames come from the main loop
/// (one command per frame), so rendering commands have nothing to wait for.
class InteractiveHost final : public ScriptHost {
 public:
  InteractiveHost(ToolHost& tools, glm::ivec2 framebuffer) : tools_(tools), framebuffer_(framebuffer) {}
  accel::Status resize(int width, int height) override {
    tools_.resize_window(width, height);
    return {};
  }
  void render(int) override {}
  accel::Status screenshot(const std::string&) override {
    tools_.tool<Recorder>().request_screenshot();  // written at the end of this frame, numbered
    return {};
  }
  double measure_frames(int) override { return 0.0; }
  glm::ivec2 framebuffer_size() const override { return framebuffer_; }
  std::string gl_renderer() const override { return ""; }

 private:
  ToolHost& tools_;
  glm::ivec2 framebuffer_;
};

}  // namespace

accel::Status ToolHost::load_playlist(const std::string& path) {
  if (auto st = tool<PlaylistTool>().load(path); !st) return st;
  go_to_state(0);
  return {};
}

void ToolHost::go_to_state(size_t index) {
  // Going back replays from the first state: what a state may have changed returns to the
  // viewer's defaults first (the scene, structure and ray come from the states themselves).
  if (tool<PlaylistTool>().go(index)) {
    layout().reset();
    notify(ToolEvent::PlaylistReset);
  }
  refresh_title();
}

void ToolHost::run_playlist(ScriptHost* host) {
  PlaylistTool& playlist = tool<PlaylistTool>();
  while (playlist.has_pending()) {
    // In the window: one command per frame, and none while a build runs (the next one
    // needs its structure); the window stays live meanwhile.
    if (!host && (session().building() || build().recording())) return;
    const PlaylistTool::Pending next = playlist.front();
    playlist.pop();
    InteractiveHost interactive(*this, framebuffer());
    ScriptHost& h = host ? *host : interactive;
    if (auto st = execute(*next.command, h); !st) {
      playlist.fail(script_error(playlist.playlist().name, next.command->line, st.error().message));
      return;
    }
    sync_session();
    if (!host) return;
  }
}

}  // namespace viz
