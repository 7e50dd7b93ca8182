// The cost heat map's script verbs, GL-free half (script_verbs.h). The run half is
// HeatmapTool::script_verbs().
#include "registry.h"
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"heatmap", CommandKind::Heatmap, "heatmap off|nodes|prims", "the cost heat map: nodes visited or triangles tested",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 1 || (a[0] != "off" && a[0] != "nodes" && a[0] != "prims")) return a.usage_error();
       c.name = a[0];
       return "";
     }},
    {"heatmap-scale", CommandKind::HeatmapScale, "heatmap-scale auto | heatmap-scale LO HI",
     "its colour scale: 0..p99 of each image, or fixed (kept across structures, so their images compare)",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() == 1 && a[0] == "auto") {
         c.on = false;
         return "";
       }
       if (a.size() != 2) return a.usage_error();
       if (std::string e = a.finite_values(0, 2, c); !e.empty()) return "heatmap-scale: " + e;
       if (!(c.values[0] >= 0.0f && c.values[0] < c.values[1]))
         return "heatmap-scale: expected 0 <= LO < HI, got " + a[0] + " " + a[1];
       c.on = true;
       return "";
     }},
    {"heatmap-diff", CommandKind::HeatmapDiff, "heatmap-diff NAME [key=value ...] | heatmap-diff off",
     "the difference view: the current structure's cost minus NAME's per pixel, diverging colours",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() < 1) return a.usage_error();
       c.on = !(a.size() == 1 && a[0] == "off");
       if (!c.on) return "";
       c.name = a[0];
       c.params.assign(a.words().begin() + 1, a.words().end());
       auto choice = accel::parse_structure(c.name, c.params);
       return choice ? "" : "heatmap-diff: " + choice.error().message;
     }},
    {"print-heatmap", CommandKind::PrintHeatmap, "print-heatmap",
     "`heat map: METRIC WxH, scale LO..HI (auto|fixed), mean M, max X`", parse_no_words},
};

}  // namespace

std::span<const ScriptVerb> heatmap_verbs() { return kVerbs; }

}  // namespace viz
