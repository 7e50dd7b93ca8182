// libFuzzer target: the bench JSON the speed-against-error chart reads (--bench-json,
// app/viewer/bench_chart.cpp), then the chart of every group with every x / y choice: what
// loads must place every point inside the chart, with finite coordinates.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "bench_chart.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto bench = viz::parse_bench_json(text, "fuzz.json");
  if (!bench) {
    if (bench.error().message.find('\n') != std::string::npos) std::abort();
    return 0;
  }
  const viz::BenchData& d = bench.value();
  if (d.rows.empty()) return 0;
  for (size_t g = 0; g < d.groups.size() && g < 8; ++g)
    for (viz::ChartX x : {viz::ChartX::ErrorRate, viz::ChartX::MaxRelTErr})
      for (bool log_y : {false, true}) {
        viz::ChartOptions options;
        options.group = g;
        options.x = x;
        options.log_y = log_y;
        const viz::ChartModel chart = viz::make_chart(d, options);
        for (const viz::ChartPoint& p : chart.points)
          if (!std::isfinite(p.fx) || !std::isfinite(p.fy) || p.fx < -1e-3f || p.fx > 1.001f || p.fy < -1e-3f ||
              p.fy > 1.001f)
            std::abort();
      }
  return 0;
}
