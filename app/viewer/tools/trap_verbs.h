#pragma once
// The lecture traps' script verbs (commands.h). GL-free: the catalogue (script_verbs.h)
// reads them without their runs; TrapTool::add_verbs() binds them to the tool.
#include <string>

#include "commands.h"
#include "traps.h"

namespace viz {

template <class Verbs>
void trap_verbs(Verbs& verbs) {
  verbs.template add<Word>(
      "trap", "trap pq|kd|grid", "load a lecture trap's scene and structure, shoot its ray",
      [](const VerbArgs& a, Word& s) -> std::string {
        if (a.size() != 1) return a.usage_error();
        if (auto demo = accel::trap_demo(a[0]); !demo) return "trap: " + demo.error().message;
        s.word = a[0];
        return "";
      },
      [](auto&, auto& host, const Word& name, ScriptHost& script) -> accel::Status {
        script.render(1);  // the current layout, so the scene is framed into the 3D view
        return host.load_trap(name.word);
      });
  verbs.template add<NoArgs>(
      "print-naive", "print-naive",
      "`naive hit PRIM T` or `naive miss`: what a traversal stopping at the first leaf with a hit would answer",
      parse_no_words, [](auto&, auto& host, const NoArgs&, ScriptHost&) -> accel::Status {
        if (auto st = host.ray().need_trace(); !st) return accel::make_error("print-naive: " + st.error().message);
        print_script_line(accel::naive_line(accel::naive_first_leaf_hit(host.ray().ray().player.events())));
        return {};
      });
  verbs.template add<NoArgs>(
      "print-trap", "print-trap",
      "`trap NAME: TITLE` while the trap's explanation applies (its scene and structure with its parameters), "
      "else `trap: none`",
      parse_no_words, [](auto& trap, auto& host, const NoArgs&, ScriptHost&) -> accel::Status {
        print_script_line(trap.trap_line(host.session().current()));
        return {};
      });
}

}  // namespace viz
