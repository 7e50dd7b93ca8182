// The blackboard's (2D mode) script verbs, GL-free half (script_verbs.h). The run half is
// App::blackboard_verbs() in app_blackboard.cpp, where the 2D mode lives.
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"mode", CommandKind::Mode, "mode 2d|3d",
     "the blackboard (a 2D scene in the plane z = 0 seen from above: the current 2D scene, else an empty board), or "
     "back to the last 3D scene",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 1 || (a[0] != "2d" && a[0] != "3d")) return a.usage_error();
       c.on = a[0] == "2d";
       return "";
     }},
    {"scene2d", CommandKind::Scene2d, "scene2d FILE", "load a 2D scene file (docs/hits.md) onto the blackboard",
     parse_one_word},
    {"add2d", CommandKind::Add2d, "add2d tri X1 Y1 X2 Y2 X3 Y3",
     "add a triangle to the blackboard (rebuilds, replays the ray)",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 7 || a[0] != "tri") return a.usage_error();
       return a.finite_values(1, 6, c);
     }},
    {"ray2d", CommandKind::Ray2d, "ray2d OX OY DX DY", "the debug ray in the plane",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 4) return a.usage_error();
       if (auto e = a.finite_values(0, 4, c); !e.empty()) return e;
       if (c.values[2] == 0.0f && c.values[3] == 0.0f) return "ray2d: the direction is zero";
       return "";
     }},
    {"save2d", CommandKind::Save2d, "save2d FILE", "write the blackboard's scene as a 2D scene file", parse_one_word},
};

}  // namespace

std::span<const ScriptVerb> blackboard_verbs() { return kVerbs; }

}  // namespace viz
