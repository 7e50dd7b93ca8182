#pragma once
// The speed-against-error chart's script verbs (commands.h). GL-free: the catalogue
// (script_verbs.h) reads them without their runs; add_bench_chart_verbs()
// (tools/bench_chart_tool.h) binds them to the chart's state.
#include <string>
#include <vector>

#include "bench_chart.h"
#include "commands.h"

namespace viz {

struct ShowChartArgs {
  bool on = false;
  std::vector<std::string> settings;  ///< x=..., speed=..., y=..., labels=..., group=N
};

template <class Verbs>
void bench_chart_verbs(Verbs& verbs) {
  verbs.template add<Word>(
      "load-bench", "load-bench FILE",
      "load a bench JSON (`accelviz-cli bench --out-json`) and open the \"Speed vs error\" chart", parse_one_word,
      [](auto& chart, auto&, const Word& file, ScriptHost&) -> accel::Status {
        return load_bench_into(chart, file.word);
      });
  verbs.template add<ShowChartArgs>(
      "show-chart", "show-chart on|off [x=errors|t-error] [speed=mt|1t] [y=linear|log] [labels=on|off] [group=N]",
      "show or hide the chart, with its settings",
      [](const VerbArgs& a, ShowChartArgs& s) -> std::string {
        if (a.size() < 1 || !parse_on_off(a[0], &s.on)) return a.usage_error();
        // The settings are checked here (group against the file only when it runs).
        ChartOptions check;
        for (size_t i = 1; i < a.size(); ++i)
          if (std::string e = set_chart_option(check, a[i]); !e.empty()) return "show-chart: " + e;
        s.settings.assign(a.words().begin() + 1, a.words().end());
        return "";
      },
      [](auto& chart, auto& host, const ShowChartArgs& s, ScriptHost&) -> accel::Status {
        if (!s.on) {
          chart.open = false;
          return {};
        }
        if (!chart.data)
          return accel::make_error("show-chart: no bench JSON loaded (load-bench FILE or --bench-json FILE first)");
        ChartOptions options = chart.options;
        for (const std::string& setting : s.settings) set_chart_option(options, setting);  // checked by the parser
        if (options.group >= chart.data->groups.size())
          return accel::make_error("show-chart: group=" + std::to_string(options.group + 1) + ", but " +
                                   chart.data->path + " has " + std::to_string(chart.data->groups.size()) +
                                   " group(s) of scene and rays");
        chart.options = options;
        chart.open = true;
        host.show_ui();
        return {};
      });
}

}  // namespace viz
