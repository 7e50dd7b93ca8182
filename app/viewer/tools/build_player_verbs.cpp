// The construction mode's script verbs, GL-free half (script_verbs.h). The run half is
// BuildPlayer::script_verbs().
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"construct", CommandKind::Construct, "construct", "record the current structure's build (construction mode)",
     parse_no_words},
    {"build-step", CommandKind::BuildStep, "build-step N | build-step end | build-step back N | build-step start",
     "move the construction player",
     [](const VerbArgs& a, ScriptCommand& c) { return parse_step_words(a, c, /*hit=*/false); }},
    {"print-build-step", CommandKind::PrintBuildStep, "print-build-step", "`build step K/N: TEXT` (K steps applied)",
     parse_no_words},
    {"sah-plot", CommandKind::SahPlot, "sah-plot on|off", "the construction panel's SAH cost plot", parse_on_off_word},
};

}  // namespace

std::span<const ScriptVerb> build_player_verbs() { return kVerbs; }

}  // namespace viz
