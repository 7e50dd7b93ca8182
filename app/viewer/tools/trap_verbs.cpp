// The lecture traps' script verbs, GL-free half (script_verbs.h). The run half is
// TrapTool::script_verbs().
#include "script_verbs.h"
#include "traps.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"trap", CommandKind::Trap, "trap pq|kd|grid", "load a lecture trap's scene and structure, shoot its ray",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 1) return a.usage_error();
       if (auto demo = accel::trap_demo(a[0]); !demo) return "trap: " + demo.error().message;
       c.name = a[0];
       return "";
     }},
    {"print-naive", CommandKind::PrintNaive, "print-naive",
     "`naive hit PRIM T` or `naive miss`: what a traversal stopping at the first leaf with a hit would answer",
     parse_no_words},
    {"print-trap", CommandKind::PrintTrap, "print-trap",
     "`trap NAME: TITLE` while the trap's explanation applies (its scene and structure with its parameters), "
     "else `trap: none`",
     parse_no_words},
};

}  // namespace

std::span<const ScriptVerb> trap_verbs() { return kVerbs; }

}  // namespace viz
