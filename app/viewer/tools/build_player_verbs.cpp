// The construction mode's script verbs, GL-free half (script_verbs.h). The run half is
// BuildPlayer::script_verbs().
#include <charconv>

#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"construct", CommandKind::Construct, "construct", "record the current structure's build (construction mode)",
     parse_no_words},
    {"construct-until", CommandKind::ConstructUntil, "construct-until N",
     "a student's failed build replayed up to the fault (`accelviz-cli check` writes it): record the current "
     "structure's build stopped right after its N-th build-log call and show its last step; the `structure` line "
     "before it builds only as far",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 1) return a.usage_error();
       const std::string& w = a[0];
       const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), c.calls);
       if (ec != std::errc() || end != w.data() + w.size() || c.calls == 0)
         return "construct-until: N must be a whole number of build-log calls, at least 1, got '" + w +
                "' (a build that failed before its first call has nothing to replay)";
       return "";
     }},
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
