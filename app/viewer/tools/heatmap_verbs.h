#pragma once
// The cost heat map's script verbs (commands.h). GL-free: the catalogue (script_verbs.h)
// reads them without their runs; HeatmapTool::add_verbs() binds them to the tool.
#include <optional>
#include <string>

#include "built_structure.h"
#include "commands.h"
#include "heatmap.h"
#include "registry.h"
#include "tools/heatmap_scale.h"

namespace viz {

struct HeatmapArgs {
  std::optional<accel::CostMetric> metric;  ///< nullopt: off
};

struct HeatmapDiffArgs {
  std::optional<StructureRequest> other;  ///< nullopt: off
};

/// After a change the image depends on: computed now in script mode, from the camera as
/// drawn.
template <class Heatmap, class Host>
accel::Status recompute_heatmap(Heatmap& heatmap, Host& host, ScriptHost& script) {
  host.settle_camera(script);
  if (auto st = host.session().need_structure(); !st) return st;
  heatmap.compute_now(host.heatmap_view());
  return {};
}

template <class Verbs>
void heatmap_verbs(Verbs& verbs) {
  verbs.template add<HeatmapArgs>(
      "heatmap", "heatmap off|nodes|prims", "the cost heat map: nodes visited or triangles tested",
      [](const VerbArgs& a, HeatmapArgs& s) -> std::string {
        if (a.size() != 1 || (a[0] != "off" && a[0] != "nodes" && a[0] != "prims")) return a.usage_error();
        if (a[0] == "off") return "";
        accel::CostMetric metric = accel::CostMetric::NodesVisited;
        accel::parse_cost_metric(a[0], &metric);  // "nodes" or "prims"
        s.metric = metric;
        return "";
      },
      [](auto& heatmap, auto& host, const HeatmapArgs& s, ScriptHost& script) -> accel::Status {
        heatmap.set_on(s.metric.has_value());
        if (!heatmap.on()) return {};
        heatmap.set_metric(*s.metric);
        return recompute_heatmap(heatmap, host, script);
      });
  verbs.template add<HeatmapScale>(
      "heatmap-scale", "heatmap-scale auto | heatmap-scale LO HI",
      "its colour scale: 0..p99 of each image, or fixed (kept across structures, so their images compare)",
      [](const VerbArgs& a, HeatmapScale& s) -> std::string {
        if (a.size() == 1 && a[0] == "auto") {
          s.fixed = false;
          return "";
        }
        if (a.size() != 2) return a.usage_error();
        float range[2];
        if (std::string e = a.finite_values(0, range); !e.empty()) return "heatmap-scale: " + e;
        if (!(range[0] >= 0.0f && range[0] < range[1]))
          return "heatmap-scale: expected 0 <= LO < HI, got " + a[0] + " " + a[1];
        s = {true, range[0], range[1]};
        return "";
      },
      [](auto& heatmap, auto&, const HeatmapScale& s, ScriptHost&) -> accel::Status {
        heatmap.set_scale(s);
        return {};
      });
  verbs.template add<HeatmapDiffArgs>(
      "heatmap-diff", "heatmap-diff NAME [key=value ...] | heatmap-diff off",
      "the difference view: the current structure's cost minus NAME's per pixel, diverging colours",
      [](const VerbArgs& a, HeatmapDiffArgs& s) -> std::string {
        if (a.size() < 1) return a.usage_error();
        if (a.size() == 1 && a[0] == "off") return "";
        StructureRequest& other = s.other.emplace();
        other.name = a[0];
        other.params.assign(a.words().begin() + 1, a.words().end());
        auto choice = accel::parse_structure(other.name, other.params);
        return choice ? "" : "heatmap-diff: " + choice.error().message;
      },
      [](auto& heatmap, auto& host, const HeatmapDiffArgs& s, ScriptHost& script) -> accel::Status {
        heatmap.set_difference(s.other);
        if (!heatmap.on()) return {};
        if (auto st = recompute_heatmap(heatmap, host, script); !st) return st;
        if (!heatmap.error().empty()) return accel::make_error(heatmap.error());
        return {};
      });
  verbs.template add<NoArgs>("print-heatmap", "print-heatmap",
                             "`heat map: METRIC WxH, scale LO..HI (auto|fixed), mean M, max X`", parse_no_words,
                             [](auto& heatmap, auto&, const NoArgs&, ScriptHost&) -> accel::Status {
                               print_script_line(heatmap.summary());
                               return {};
                             });
}

}  // namespace viz
