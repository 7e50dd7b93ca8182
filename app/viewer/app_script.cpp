// App, part 3: script dispatch and App's own verbs. Each command goes to the run row of its
// kind (App::App() joined the tools' rows, commands.h); the verbs here are the viewer's
// global ones (the window, the camera, the panels, colours, screenshots, the saved state).
// Builds, heat maps, comparisons and sweeps run synchronously in script mode, so every
// command sees the result of the previous one; screenshots go through the ScriptHost
// (main.cpp).
#include <cstdio>

#include "app.h"
#include "color_scheme.h"
#include "tools/structure_session.h"
#include "tools/node_display.h"

namespace viz {

accel::Status App::execute(const ScriptCommand& c, ScriptHost& host) {
  const auto run = runs_.find(c.kind);
  if (run == runs_.end()) return accel::make_error("no tool runs this command");  // App::App() checks every verb
  return run->second(c, host);
}

std::vector<VerbRun> App::global_verbs() {
  return {
      {CommandKind::Size,
       [this](const ScriptCommand& c, ScriptHost& host) -> accel::Status {
         if (auto st = host.resize(c.ints[0], c.ints[1]); !st) return st;
         layout_.set_framebuffer(host.framebuffer_size());
         layout_.relayout();
         return {};
       }},
      {CommandKind::Camera,
       [this](const ScriptCommand& c, ScriptHost&) -> accel::Status {
         const glm::vec3 eye(c.values[0], c.values[1], c.values[2]), target(c.values[3], c.values[4], c.values[5]);
         const float fov = c.has_fov ? c.values[6] : camera_.pinhole().fovy_deg;
         camera_.look_at(eye, target, fov, session().scene());
         return {};
       }},
      {CommandKind::Panel,
       [this](const ScriptCommand& c, ScriptHost&) -> accel::Status {
         set_panel(c.name, c.on);
         return {};
       }},
      {CommandKind::Large,
       [this](const ScriptCommand& c, ScriptHost& host) -> accel::Status {
         layout_.set_lecture(c.on);
         host.render(2);  // the font switches at the next frame
         return {};
       }},
      {CommandKind::Colors,
       [this](const ScriptCommand& c, ScriptHost&) -> accel::Status {
         ColorScheme scheme;
         parse_colormap(c.name, &scheme.map);  // checked by the parser
         scheme.cvd_safe_hits = c.on;
         set_color_scheme(scheme);
         notify(ToolEvent::ColorsChanged);
         return {};
       }},
      {CommandKind::Screenshot,
       [](const ScriptCommand& c, ScriptHost& host) -> accel::Status { return host.screenshot(c.name); }},
      {CommandKind::SaveState,
       [this](const ScriptCommand& c, ScriptHost&) -> accel::Status { return save_state(c.name); }},
      {CommandKind::PrintFrameTime,
       [this](const ScriptCommand& c, ScriptHost& host) -> accel::Status {
         const double ms = host.measure_frames(c.ints[0]);
         const glm::ivec2 fb = host.framebuffer_size();
         std::printf("frame-time %.2f ms (mean of %d frames, %dx%d, %zu triangles, %zu nodes drawn, GL: %s)\n", ms,
                     c.ints[0], fb.x, fb.y, session().scene().triangle_count(), tool<NodeDisplay>().drawn_nodes(),
                     host.gl_renderer().c_str());
         std::fflush(stdout);
         return {};
       }},
  };
}

}  // namespace viz
