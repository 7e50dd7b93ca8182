#pragma once
// The parameter sweep's script verb (commands.h). GL-free: the catalogue (script_verbs.h)
// reads it without its run; SweepTool::add_verbs() binds it to the tool.
#include <string>

#include "commands.h"

namespace viz {

struct SweepArgs {
  std::string param;
  float lo = 0.0f, hi = 0.0f;
  int steps = 0;
};

template <class Verbs>
void sweep_verbs(Verbs& verbs) {
  verbs.template add<SweepArgs>(
      "sweep", "sweep PARAM LO HI STEPS", "parameter sweep of the current structure",
      [](const VerbArgs& a, SweepArgs& s) -> std::string {
        if (a.size() != 4) return a.usage_error();
        s.param = a[0];
        if (!parse_finite(a[1], &s.lo) || !parse_finite(a[2], &s.hi) || !parse_script_int(a[3], &s.steps) ||
            s.steps < 2 || s.steps > 64 || !(s.lo < s.hi))
          return "sweep: expected PARAM LO HI STEPS with LO < HI and 2 <= STEPS <= 64";
        return "";
      },
      [](auto& sweep, auto& host, const SweepArgs& s, ScriptHost& script) -> accel::Status {
        if (auto st = host.session().need_structure(); !st) return st;
        if (auto st = sweep.configure(host.session().editor_info(), s.param, s.lo, s.hi, s.steps); !st) return st;
        host.settle_camera(script);
        return host.start_sweep();
      });
}

}  // namespace viz
