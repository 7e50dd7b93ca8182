#pragma once
// The tree diagram's script verbs (commands.h). GL-free: the catalogue (script_verbs.h)
// reads them without their runs; TreeDiagram::add_verbs() binds them to the diagram.
#include <string>

#include "commands.h"
#include "trace.h"

namespace viz {

struct TreeSelectArgs {
  int node = 0;
  bool isolate = false;  ///< draw only its subtree in 3D
};

template <class Verbs>
void tree_diagram_verbs(Verbs& verbs) {
  verbs.template add<OnOff>("tree", "tree on|off", "the \"Tree\" window: the hierarchy diagram (grid: the cell walk)",
                            parse_on_off_word,
                            [](auto& tree, auto& host, const OnOff& s, ScriptHost&) -> accel::Status {
                              if (tree.on() != s.on) host.relayout();
                              tree.set_on(s.on);
                              if (s.on) host.show_ui();
                              return {};
                            });
  verbs.template add<TreeSelectArgs>(
      "tree-select", "tree-select NODE [isolate]",
      "select node NODE in the tree (3D highlight, numbers); isolate: draw only its subtree in 3D",
      [](const VerbArgs& a, TreeSelectArgs& s) -> std::string {
        if (a.size() < 1 || a.size() > 2 || (a.size() == 2 && a[1] != "isolate")) return a.usage_error();
        if (!parse_script_int(a[0], &s.node) || s.node < 0)
          return "tree-select: '" + a[0] + "' is not a node id (an integer >= 0)";
        s.isolate = a.size() == 2;
        return "";
      },
      [](auto& tree, auto& host, const TreeSelectArgs& s, ScriptHost&) -> accel::Status {
        if (auto st = host.session().need_structure(); !st)
          return accel::make_error("tree-select: " + st.error().message);
        tree.follow(host.session().current_ptr(), host.ray().ray(),
                    host.build().active() ? host.build().replay() : nullptr);
        if (auto st = tree.select(static_cast<accel::NodeId>(s.node), s.isolate); !st) return st;
        host.show_ui();
        return {};
      });
}

}  // namespace viz
