#pragma once
// The ray debugger's script verbs (commands.h): the debug ray, stepping through its
// traversal, and what it prints. GL-free: the catalogue (script_verbs.h) reads them without
// their runs; RayDebugger::add_verbs() binds them to the debugger.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "commands.h"
#include "geometry.h"
#include "rays_io.h"
#include "tools/false_claims.h"
#include "tools/traversal_numbers.h"

namespace viz {

struct PixelArgs {
  float x = 0.0f, y = 0.0f;  ///< from the top-left
};

struct RayArgs {
  accel::Ray ray;
};

/// `ray`'s words: six finite numbers, then as in a rays file TMIN and a TMAX that may be
/// inf, TMIN <= TMAX.
inline std::string parse_ray_words(const VerbArgs& a, RayArgs& s) {
  if (a.size() != 6 && a.size() != 8) return a.usage_error();
  float v[6];
  if (auto e = a.finite_values(0, v); !e.empty()) return e;
  if (v[3] == 0.0f && v[4] == 0.0f && v[5] == 0.0f) return "ray: the direction is zero";
  s.ray.org = {v[0], v[1], v[2]};
  s.ray.dir = {v[3], v[4], v[5]};
  s.ray.tmin = 0.0f;
  s.ray.tmax = std::numeric_limits<float>::infinity();
  if (a.size() == 8) {
    if (!parse_finite(a[6], &s.ray.tmin)) return "'" + a[6] + "' is not a finite number (" + a.usage() + ")";
    if (!accel::parse_ray_number(a[7], &s.ray.tmax) || std::isnan(s.ray.tmax) || s.ray.tmax == -INFINITY)
      return "'" + a[7] + "' is not a number or inf (" + a.usage() + ")";
    if (!(s.ray.tmin <= s.ray.tmax)) return "ray: TMIN is greater than TMAX";
  }
  return "";
}

template <class Verbs>
void ray_debugger_verbs(Verbs& verbs) {
  verbs.template add<PixelArgs>(
      "ray-at-pixel", "ray-at-pixel X Y", "shoot like a click; pixel from the top-left",
      [](const VerbArgs& a, PixelArgs& s) -> std::string {
        if (a.size() != 2) return a.usage_error();
        float xy[2];
        if (auto e = a.finite_values(0, xy); !e.empty()) return e;
        s = {xy[0], xy[1]};
        return "";
      },
      [](auto& debugger, auto& host, const PixelArgs& s, ScriptHost& script) -> accel::Status {
        return debugger.ray_at_pixel(host, s.x, s.y, script);
      });
  verbs.template add<RayArgs>("ray", "ray OX OY OZ DX DY DZ [TMIN TMAX]", "shoot a given ray (TMAX may be `inf`)",
                              parse_ray_words, [](auto&, auto& host, const RayArgs& s, ScriptHost&) -> accel::Status {
                                host.set_ray(s.ray, "script");
                                return {};
                              });
  verbs.template add<PlayerMove>(
      "step", "step N | step end | step back N | step hit | step start", "move the traversal player",
      [](const VerbArgs& a, PlayerMove& s) { return parse_step_words(a, s, /*hit=*/true); },
      [](auto& debugger, auto& host, const PlayerMove& s, ScriptHost& script) -> accel::Status {
        if (auto st = debugger.need_trace(); !st) return st;
        auto& p = debugger.player();
        p.pause();
        host.build().set_active(false);  // stepping the ray: back to the traversal's panels
        const size_t from = p.step();
        if (s.mode == StepMode::Hit)
          p.jump_to_hit();
        else
          step_clock(p, s.mode, static_cast<size_t>(s.count));  // transport_controls.h
        host.walk_recorded(p, from, script);
        return {};
      });
  verbs.template add<Word>(
      "frames", "frames PREFIX", "`PREFIX0000.png` ... one PNG per remaining step", parse_one_word,
      [](auto& debugger, auto&, const Word& prefix, ScriptHost& script) -> accel::Status {
        if (auto st = debugger.need_trace(); !st) return st;
        constexpr size_t kMaxFrames = 5000;
        auto& p = debugger.player();
        const size_t first = p.step(), last = p.size() - 1;
        if (last - first + 1 > kMaxFrames)
          return accel::make_error("frames: " + std::to_string(last - first + 1) + " steps remain; at most " +
                                   std::to_string(kMaxFrames) + " frames (step closer to the end first)");
        for (size_t step = first; step <= last; ++step) {
          p.seek(step);
          char path[4096];
          std::snprintf(path, sizeof path, "%s%04zu.png", prefix.word.c_str(), step);
          if (auto st = script.screenshot(path); !st) return st;
        }
        return {};
      });
  verbs.template add<NoArgs>("print-hit", "print-hit", "`hit PRIM T` or `miss`", parse_no_words,
                             [](auto& debugger, auto&, const NoArgs&, ScriptHost&) -> accel::Status {
                               if (auto st = debugger.need_ray(); !st) return st;
                               print_script_line(debugger.hit_line());
                               return {};
                             });
  verbs.template add<NoArgs>("print-step", "print-step", "the current step as one line", parse_no_words,
                             [](auto& debugger, auto&, const NoArgs&, ScriptHost&) -> accel::Status {
                               if (auto st = debugger.need_trace(); !st) return st;
                               print_script_line(debugger.step_line());
                               return {};
                             });
  verbs.template add<NoArgs>("print-ray", "print-ray",
                             "the ray as C99 hex floats, `ox oy oz dx dy dz` (a rays-file line)", parse_no_words,
                             [](auto& debugger, auto&, const NoArgs&, ScriptHost&) -> accel::Status {
                               if (auto st = debugger.need_ray(); !st) return st;
                               print_script_line(debugger.ray_line());
                               return {};
                             });
  verbs.template add<NoArgs>(
      "print-vars", "print-vars",
      "`vars: name=value ...` of the current step (the traversal's recorded variables, closest_hit, the stack or "
      "queue as NODE:KEY,...)",
      parse_no_words, [](auto& debugger, auto& host, const NoArgs&, ScriptHost&) -> accel::Status {
        if (auto st = debugger.need_trace(); !st) return accel::make_error("print-vars: " + st.error().message);
        const auto* built = host.session().current();
        const auto& ray = debugger.ray();
        const auto& events = ray.player.events();
        print_script_line(vars_line(ray.vars, events, accel::trace_highlight(events, ray.player.step()),
                                    built ? built->kind : TraversalKind::Unknown));
        return {};
      });
  verbs.template add<NoArgs>(
      "print-claims", "print-claims",
      "a student's structure: `claim STEP: CAUSE: CLAIM -- TRUTH` per logged claim the kit found false on this walk "
      "(STEP as print-step counts), or `claims: none`",
      parse_no_words, [](auto& debugger, auto&, const NoArgs&, ScriptHost&) -> accel::Status {
        if (auto st = debugger.need_trace(); !st) return accel::make_error("print-claims: " + st.error().message);
        for (const std::string& line : claims_lines(debugger.ray().audit)) print_script_line(line);
        return {};
      });
}

}  // namespace viz
