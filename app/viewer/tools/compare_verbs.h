#pragma once
// The comparison's script verb (commands.h). GL-free: the catalogue (script_verbs.h) reads
// it without its run; CompareTool::add_verbs() binds it to the tool.
#include <string>

#include "commands.h"

namespace viz {

template <class Verbs>
void compare_verbs(Verbs& verbs) {
  verbs.template add<NoArgs>(
      "compare", "compare",
      "fill the \"same ray, every structure\" table; for a student's structure also print `compare-builtin` lines "
      "against the built-in of its kind set up like it: the first difference in what the walks mean (its first false "
      "claim, a nearest hit one walk never tests), and which answer is right ([the kit](student.md#in-the-viewer))",
      [](const VerbArgs& a, NoArgs&) -> std::string { return a.size() == 0 ? "" : a.usage_error(); },
      [](auto& compare, auto& host, const NoArgs&, ScriptHost&) -> accel::Status {
        if (auto st = host.ray().need_trace(); !st) return st;
        host.start_compare();
        compare.set_open(true);
        compare.print_rows();
        return {};
      });
}

}  // namespace viz
