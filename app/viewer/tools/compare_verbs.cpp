// The comparison's script verb, GL-free half (script_verbs.h). The run half is
// CompareTool::script_verbs().
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"compare", CommandKind::Compare, "compare",
     "fill the \"same ray, every structure\" table; for a student's structure also print `compare-builtin` lines "
     "against the built-in of its kind set up like it: the first difference in what the walks mean (its first false "
     "claim, a nearest hit one walk never tests), and which answer is right ([the kit](student.md#in-the-viewer))",
     [](const VerbArgs& a, ScriptCommand&) -> std::string { return a.size() == 0 ? "" : a.usage_error(); }},
};

}  // namespace

std::span<const ScriptVerb> compare_verbs() { return kVerbs; }

}  // namespace viz
