// The node display's script verbs, GL-free half (script_verbs.h): which nodes are drawn and
// how, and the mesh. The run half is NodeDisplay::script_verbs().
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"show", CommandKind::Show, "show depth=A..B | show depth=A | show leaves | show all", "which nodes are drawn",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 1) return a.usage_error();
       if (a[0] == "all") {
         c.show = ShowMode::All;
       } else if (a[0] == "leaves") {
         c.show = ShowMode::Leaves;
       } else if (a[0].starts_with("depth=")) {
         c.show = ShowMode::Depth;
         const std::string range = a[0].substr(6);
         const size_t dots = range.find("..");
         const std::string lo = range.substr(0, dots), hi = dots == std::string::npos ? lo : range.substr(dots + 2);
         if (!parse_script_int(lo, &c.ints[0]) || !parse_script_int(hi, &c.ints[1]) || c.ints[0] < 0 ||
             c.ints[1] < c.ints[0])
           return "show: '" + a[0] + "' is not depth=A..B with 0 <= A <= B";
       } else {
         return a.usage_error();
       }
       return "";
     }},
    {"mesh", CommandKind::Mesh, "mesh solid|translucent|wireframe|off", "how the mesh is drawn",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 1 || (a[0] != "solid" && a[0] != "translucent" && a[0] != "wireframe" && a[0] != "off"))
         return a.usage_error();
       c.name = a[0];
       return "";
     }},
    {"empty-cells", CommandKind::EmptyCells, "empty-cells on|off", "grid: draw empty cells too", parse_on_off_word},
    {"nodes", CommandKind::Nodes, "nodes on|off", "draw the structure's nodes (the ray's highlights stay)",
     parse_on_off_word},
    {"opacity", CommandKind::Opacity, "opacity A", "opacity of the structure's lines, 0.05..1",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 1 || !parse_finite(a[0], &c.values[0]) || c.values[0] < 0.05f || c.values[0] > 1.0f)
         return a.usage_error() + " (a number in 0.05..1)";
       return "";
     }},
};

}  // namespace

std::span<const ScriptVerb> node_display_verbs() { return kVerbs; }

}  // namespace viz
