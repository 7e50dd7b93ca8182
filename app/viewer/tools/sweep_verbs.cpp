// The parameter sweep's script verb, GL-free half (script_verbs.h). The run half is
// SweepTool::script_verbs().
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"sweep", CommandKind::Sweep, "sweep PARAM LO HI STEPS", "parameter sweep of the current structure",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 4) return a.usage_error();
       c.name = a[0];
       float lo, hi;
       if (!parse_finite(a[1], &lo) || !parse_finite(a[2], &hi) || !parse_script_int(a[3], &c.ints[0]) ||
           c.ints[0] < 2 || c.ints[0] > 64 || !(lo < hi))
         return "sweep: expected PARAM LO HI STEPS with LO < HI and 2 <= STEPS <= 64";
       c.values[0] = lo;
       c.values[1] = hi;
       return "";
     }},
};

}  // namespace

std::span<const ScriptVerb> sweep_verbs() { return kVerbs; }

}  // namespace viz
