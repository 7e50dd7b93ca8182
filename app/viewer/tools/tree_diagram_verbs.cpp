// The tree diagram's script verbs, GL-free half (script_verbs.h). The run half is
// TreeDiagram::script_verbs().
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"tree", CommandKind::Tree, "tree on|off", "the \"Tree\" window: the hierarchy diagram (grid: the cell walk)",
     parse_on_off_word},
    {"tree-select", CommandKind::TreeSelect, "tree-select NODE [isolate]",
     "select node NODE in the tree (3D highlight, numbers); isolate: draw only its subtree in 3D",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() < 1 || a.size() > 2 || (a.size() == 2 && a[1] != "isolate")) return a.usage_error();
       if (!parse_script_int(a[0], &c.ints[0]) || c.ints[0] < 0)
         return "tree-select: '" + a[0] + "' is not a node id (an integer >= 0)";
       c.on = a.size() == 2;  // isolate
       return "";
     }},
};

}  // namespace

std::span<const ScriptVerb> tree_diagram_verbs() { return kVerbs; }

}  // namespace viz
