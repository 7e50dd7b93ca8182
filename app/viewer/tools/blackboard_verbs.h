#pragma once
// The blackboard's (2D mode) script verbs (commands.h). GL-free: the catalogue
// (script_verbs.h) reads them without their runs; BlackboardTool::add_verbs() binds them to
// the tool.
#include <array>
#include <string>

#include "commands.h"

namespace viz {

struct Mode2dArgs {
  bool planar = false;  ///< `mode 2d`
};

struct Triangle2dArgs {
  std::array<float, 6> xy{};  ///< x1 y1 x2 y2 x3 y3
};

struct Ray2dArgs {
  std::array<float, 4> values{};  ///< ox oy dx dy
};

template <class Verbs>
void blackboard_verbs(Verbs& verbs) {
  verbs.template add<Mode2dArgs>(
      "mode", "mode 2d|3d",
      "the blackboard (a 2D scene in the plane z = 0 seen from above: the current 2D scene, else an empty board), or "
      "back to the last 3D scene",
      [](const VerbArgs& a, Mode2dArgs& s) -> std::string {
        if (a.size() != 1 || (a[0] != "2d" && a[0] != "3d")) return a.usage_error();
        s.planar = a[0] == "2d";
        return "";
      },
      [](auto& board, auto& host, const Mode2dArgs& s, ScriptHost& script) -> accel::Status {
        if (auto st = board.set_mode_2d(s.planar, host); !st) return st;
        host.settle_camera(script);
        return {};
      });
  verbs.template add<Word>("scene2d", "scene2d FILE", "load a 2D scene file (docs/hits.md) onto the blackboard",
                           parse_one_word,
                           [](auto& board, auto& host, const Word& file, ScriptHost& script) -> accel::Status {
                             if (auto st = board.load_scene2d(file.word, host); !st) return st;
                             host.settle_camera(script);
                             return {};
                           });
  verbs.template add<Triangle2dArgs>(
      "add2d", "add2d tri X1 Y1 X2 Y2 X3 Y3", "add a triangle to the blackboard (rebuilds, replays the ray)",
      [](const VerbArgs& a, Triangle2dArgs& s) -> std::string {
        if (a.size() != 7 || a[0] != "tri") return a.usage_error();
        return a.finite_values(1, s.xy);
      },
      [](auto& board, auto& host, const Triangle2dArgs& s, ScriptHost&) -> accel::Status {
        return board.add_triangle_2d(s.xy, host);
      });
  verbs.template add<Ray2dArgs>(
      "ray2d", "ray2d OX OY DX DY", "the debug ray in the plane",
      [](const VerbArgs& a, Ray2dArgs& s) -> std::string {
        if (a.size() != 4) return a.usage_error();
        if (auto e = a.finite_values(0, s.values); !e.empty()) return e;
        if (s.values[2] == 0.0f && s.values[3] == 0.0f) return "ray2d: the direction is zero";
        return "";
      },
      [](auto& board, auto& host, const Ray2dArgs& s, ScriptHost&) -> accel::Status {
        return board.set_ray_2d(s.values[0], s.values[1], s.values[2], s.values[3], host);
      });
  verbs.template add<Word>(
      "save2d", "save2d FILE", "write the blackboard's scene as a 2D scene file", parse_one_word,
      [](auto& board, auto& host, const Word& file, ScriptHost&) -> accel::Status {
        return board.save_scene2d(file.word, host);
      });
}

}  // namespace viz
