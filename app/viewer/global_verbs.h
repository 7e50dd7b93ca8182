#pragma once
// App's own script verbs (commands.h): the window, the camera, the panels and what they look
// like, screenshots, the saved state and the frame time. GL-free: the catalogue
// (script_verbs.h) reads the registrations without their runs; App binds them to itself
// (App::App()), a friend for the runs that set its state.
#include <cstdio>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "color_scheme.h"
#include "commands.h"
#include "tools/tool.h"

namespace viz {

class NodeDisplay;

struct SizeArgs {
  int width = 0, height = 0;
};

struct CameraArgs {
  glm::vec3 eye{0.0f}, target{0.0f};
  std::optional<float> fovy_deg;  ///< the current one when not given
};

struct PanelArgs {
  std::string panel;  ///< "all" or one panel's name
  bool on = false;
};

struct FrameTimeArgs {
  int frames = 0;
};

/// `camera`'s words: eye and target, six finite numbers, and the vertical field of view in
/// degrees if given.
inline std::string parse_camera_words(const VerbArgs& a, CameraArgs& s) {
  if (a.size() != 6 && a.size() != 7) return a.usage_error();
  float v[7] = {};
  if (auto e = a.finite_values(0, std::span<float>(v, a.size())); !e.empty()) return e;
  if (a.size() == 7 && !(v[6] > 1.0f && v[6] < 170.0f))
    return "camera: FOVY_DEG must be in (1, 170) degrees, got " + a[6];
  if (v[0] == v[3] && v[1] == v[4] && v[2] == v[5]) return "camera: eye and target are the same point";
  s.eye = {v[0], v[1], v[2]};
  s.target = {v[3], v[4], v[5]};
  if (a.size() == 7) s.fovy_deg = v[6];
  return "";
}

/// `panel`'s words: on|off for all of them, or a panel's name and on|off.
inline std::string parse_panel_words(const VerbArgs& a, PanelArgs& s) {
  if (a.size() == 1 && parse_on_off(a[0], &s.on)) {
    s.panel = "all";
    return "";
  }
  static const char* kPanels[] = {"all",   "scene",  "ray",  "steps", "code", "compare",
                                  "sweep", "legend", "vars", "strip", "trap"};
  if (a.size() != 2 || !parse_on_off(a[1], &s.on)) return a.usage_error();
  for (const char* p : kPanels) {
    if (a[0] == p) {
      s.panel = a[0];
      return "";
    }
  }
  return a.usage_error();
}

template <class Verbs>
void global_verbs(Verbs& verbs) {
  verbs.template add<SizeArgs>(
      "size", "size W H", "window size in pixels",
      [](const VerbArgs& a, SizeArgs& s) -> std::string {
        if (a.size() != 2) return a.usage_error();
        if (!parse_script_int(a[0], &s.width) || !parse_script_int(a[1], &s.height) || s.width < 64 ||
            s.height < 64 || s.width > 8192 || s.height > 8192)
          return "size: W and H must be integers in 64..8192, got '" + a[0] + " " + a[1] + "'";
        return "";
      },
      [](auto& app, auto&, const SizeArgs& s, ScriptHost& script) -> accel::Status {
        if (auto st = script.resize(s.width, s.height); !st) return st;
        app.layout_.set_framebuffer(script.framebuffer_size());
        app.layout_.relayout();
        return {};
      });
  verbs.template add<CameraArgs>(
      "camera", "camera EX EY EZ TX TY TZ [FOVY_DEG]", "place the camera",
      parse_camera_words,
      [](auto& app, auto& host, const CameraArgs& s, ScriptHost&) -> accel::Status {
        const float fov = s.fovy_deg.value_or(app.camera_.pinhole().fovy_deg);
        app.camera_.look_at(s.eye, s.target, fov, host.session().scene());
        return {};
      });
  verbs.template add<PanelArgs>(
      "panel", "panel on|off | panel scene|ray|steps|code|compare|sweep|legend|vars|strip|trap on|off",
      "all panels, or one of them (`strip`: the t-axis strip)",
      parse_panel_words,
      [](auto& app, auto&, const PanelArgs& s, ScriptHost&) -> accel::Status {
        app.set_panel(s.panel, s.on);
        return {};
      });
  verbs.template add<OnOff>(
      "large", "large on|off", "lecture mode: large fonts, high contrast", parse_on_off_word,
      [](auto& app, auto&, const OnOff& s, ScriptHost& script) -> accel::Status {
        app.layout_.set_lecture(s.on);
        script.render(2);  // the font switches at the next frame
        return {};
      });
  verbs.template add<ColorScheme>(
      "colors", "colors viridis|cividis|turbo [hits=blue-orange|green-red]",
      "the colour map of depths, counts and the heat map, and the hit / miss pair (defaults: viridis, blue-orange)",
      [](const VerbArgs& a, ColorScheme& s) -> std::string {
        if (a.size() < 1 || a.size() > 2 || !parse_colormap(a[0], &s.map)) return a.usage_error();
        s.cvd_safe_hits = true;  // hits=blue-orange
        if (a.size() == 2) {
          if (a[1] == "hits=blue-orange")
            s.cvd_safe_hits = true;
          else if (a[1] == "hits=green-red")
            s.cvd_safe_hits = false;
          else
            return a.usage_error();
        }
        return "";
      },
      [](auto&, auto& host, const ColorScheme& s, ScriptHost&) -> accel::Status {
        set_color_scheme(s);
        host.notify(ToolEvent::ColorsChanged);
        return {};
      });
  verbs.template add<Word>("screenshot", "screenshot PATH", "write a PNG", parse_one_word,
                           [](auto&, auto&, const Word& path, ScriptHost& script) -> accel::Status {
                             return script.screenshot(path.word);
                           });
  verbs.template add<Word>(
      "save-state", "save-state FILE",
      "write the viewer's state (scene, structure, kernel, camera, ray, step) as the script that restores it "
      "(`accelviz --restore FILE`)",
      parse_one_word,
      [](auto& app, auto&, const Word& file, ScriptHost&) -> accel::Status { return app.save_state(file.word); });
  verbs.template add<FrameTimeArgs>(
      "print-frame-time", "print-frame-time N", "render N frames, print the mean frame time",
      [](const VerbArgs& a, FrameTimeArgs& s) -> std::string {
        if (a.size() != 1 || !parse_script_int(a[0], &s.frames) || s.frames < 1 || s.frames > 10000)
          return a.usage_error() + " (1..10000 frames)";
        return "";
      },
      [](auto&, auto& host, const FrameTimeArgs& s, ScriptHost& script) -> accel::Status {
        const double ms = script.measure_frames(s.frames);
        const glm::ivec2 fb = script.framebuffer_size();
        std::printf("frame-time %.2f ms (mean of %d frames, %dx%d, %zu triangles, %zu nodes drawn, GL: %s)\n", ms,
                    s.frames, fb.x, fb.y, host.session().scene().triangle_count(),
                    host.template tool<NodeDisplay>().drawn_nodes(),
                    script.gl_renderer().c_str());
        std::fflush(stdout);
        return {};
      });
}

}  // namespace viz
