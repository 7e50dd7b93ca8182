// The speed-against-error chart's script verbs, GL-free half (script_verbs.h). The run half
// is bench_chart_script_verbs() in bench_chart_panel.cpp.
#include "bench_chart.h"
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"load-bench", CommandKind::LoadBench, "load-bench FILE",
     "load a bench JSON (`accelviz-cli bench --out-json`) and open the \"Speed vs error\" chart", parse_one_word},
    {"show-chart", CommandKind::ShowChart,
     "show-chart on|off [x=errors|t-error] [speed=mt|1t] [y=linear|log] [labels=on|off] [group=N]",
     "show or hide the chart, with its settings",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() < 1 || !parse_on_off(a[0], &c.on)) return a.usage_error();
       // The settings are checked here (group against the file only when it runs).
       ChartOptions check;
       for (size_t i = 1; i < a.size(); ++i)
         if (std::string e = set_chart_option(check, a[i]); !e.empty()) return "show-chart: " + e;
       c.params.assign(a.words().begin() + 1, a.words().end());
       return "";
     }},
};

}  // namespace

std::span<const ScriptVerb> bench_chart_verbs() { return kVerbs; }

}  // namespace viz
