#pragma once
// The node display's script verbs (commands.h): which nodes are drawn and how, and the mesh.
// GL-free: the catalogue (script_verbs.h) reads them without their runs;
// NodeDisplay::add_verbs() binds them to the display.
#include <string>

#include "commands.h"

namespace viz {

enum class ShowMode { All, Leaves, Depth };

struct ShowArgs {
  ShowMode mode = ShowMode::All;
  int lo = 0, hi = 0;  ///< Depth: the inclusive range
};

struct OpacityArgs {
  float alpha = 1.0f;
};

/// `show`'s words: all, leaves, depth=A..B or depth=A.
inline std::string parse_show_words(const VerbArgs& a, ShowArgs& s) {
  if (a.size() != 1) return a.usage_error();
  if (a[0] == "all") {
    s.mode = ShowMode::All;
  } else if (a[0] == "leaves") {
    s.mode = ShowMode::Leaves;
  } else if (a[0].starts_with("depth=")) {
    s.mode = ShowMode::Depth;
    const std::string range = a[0].substr(6);
    const size_t dots = range.find("..");
    const std::string lo = range.substr(0, dots), hi = dots == std::string::npos ? lo : range.substr(dots + 2);
    if (!parse_script_int(lo, &s.lo) || !parse_script_int(hi, &s.hi) || s.lo < 0 || s.hi < s.lo)
      return "show: '" + a[0] + "' is not depth=A..B with 0 <= A <= B";
  } else {
    return a.usage_error();
  }
  return "";
}

template <class Verbs>
void node_display_verbs(Verbs& verbs) {
  verbs.template add<ShowArgs>("show", "show depth=A..B | show depth=A | show leaves | show all",
                               "which nodes are drawn", parse_show_words,
                               [](auto& nodes, auto&, const ShowArgs& s, ScriptHost&) -> accel::Status {
                                 switch (s.mode) {
                                   case ShowMode::All:
                                     nodes.show_all();
                                     break;
                                   case ShowMode::Leaves:
                                     nodes.show_leaves();
                                     break;
                                   case ShowMode::Depth:
                                     nodes.show_depths(s.lo, s.hi);
                                     break;
                                 }
                                 return {};
                               });
  verbs.template add<Word>(
      "mesh", "mesh solid|translucent|wireframe|off", "how the mesh is drawn",
      [](const VerbArgs& a, Word& s) -> std::string {
        if (a.size() != 1 || (a[0] != "solid" && a[0] != "translucent" && a[0] != "wireframe" && a[0] != "off"))
          return a.usage_error();
        s.word = a[0];
        return "";
      },
      [](auto& nodes, auto&, const Word& s, ScriptHost&) -> accel::Status {
        using Mode = decltype(nodes.mesh_style().mode);  // renderer.h's MeshStyle::Mode
        nodes.set_mesh_mode(s.word == "solid"         ? Mode::Solid
                            : s.word == "translucent" ? Mode::Translucent
                            : s.word == "wireframe"   ? Mode::Wireframe
                                                      : Mode::Hidden);
        return {};
      });
  verbs.template add<OnOff>("empty-cells", "empty-cells on|off", "grid: draw empty cells too", parse_on_off_word,
                            [](auto& nodes, auto& host, const OnOff& s, ScriptHost&) -> accel::Status {
                              nodes.set_empty_cells(s.on, host.session().shown());
                              host.session().set_empty_cells(s.on);
                              return {};
                            });
  verbs.template add<OnOff>("nodes", "nodes on|off", "draw the structure's nodes (the ray's highlights stay)",
                            parse_on_off_word, [](auto& nodes, auto&, const OnOff& s, ScriptHost&) -> accel::Status {
                              nodes.set_visible(s.on);
                              return {};
                            });
  verbs.template add<OpacityArgs>(
      "opacity", "opacity A", "opacity of the structure's lines, 0.05..1",
      [](const VerbArgs& a, OpacityArgs& s) -> std::string {
        if (a.size() != 1 || !parse_finite(a[0], &s.alpha) || s.alpha < 0.05f || s.alpha > 1.0f)
          return a.usage_error() + " (a number in 0.05..1)";
        return "";
      },
      [](auto& nodes, auto&, const OpacityArgs& s, ScriptHost&) -> accel::Status {
        nodes.set_opacity(s.alpha);
        return {};
      });
}

}  // namespace viz
