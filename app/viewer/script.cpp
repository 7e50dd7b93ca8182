#include "script.h"

#include <cstdio>
#include <sstream>

#include "color_scheme.h"
#include "input_files.h"
#include "script_verbs.h"

namespace viz {
namespace {

std::vector<std::string> tokens_of(const std::string& line) {
  std::vector<std::string> tokens;
  std::istringstream in(line);
  std::string t;
  while (in >> t) {
    if (t[0] == '#') break;  // a comment runs to the end of the line
    tokens.push_back(t);
  }
  return tokens;
}

/// A failed build's replay, as `accelviz-cli check` writes it: comment lines saying what
/// failed, `scene`, `structure NAME`, `construct-until N`. The structure line's own build must
/// stop at N too, or the viewer would run the failing build in full first (the crash, the
/// runaway allocation) before the replay: it gets the N of the first construct-until after
/// it. A construct-until gets check's comment lines (`header`, the comments above the first
/// command, when they begin "accelviz-cli check:") to show what failed.
void bind_replays(std::vector<ScriptCommand>& commands, const std::vector<std::string>& header) {
  const bool from_check = !header.empty() && header[0].rfind("accelviz-cli check:", 0) == 0;
  ScriptCommand* structure = nullptr;
  for (ScriptCommand& c : commands) {
    if (c.kind == CommandKind::Structure) structure = &c;
    if (c.kind != CommandKind::ConstructUntil) continue;
    if (structure && structure->calls == 0) structure->calls = c.calls;
    if (from_check) c.params = header;
  }
}

/// The row of `verb`, or nullptr.
const ScriptVerb* find_verb(const std::string& verb) {
  for (const ScriptVerb& v : script_verbs())
    if (verb == v.verb) return &v;
  return nullptr;
}

// The verbs of App itself: the window, the camera, the panels and what they look like.
const ScriptVerb kGlobalVerbs[] = {
    {"size", CommandKind::Size, "size W H", "window size in pixels",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 2) return a.usage_error();
       if (!parse_script_int(a[0], &c.ints[0]) || !parse_script_int(a[1], &c.ints[1]) || c.ints[0] < 64 ||
           c.ints[1] < 64 || c.ints[0] > 8192 || c.ints[1] > 8192)
         return "size: W and H must be integers in 64..8192, got '" + a[0] + " " + a[1] + "'";
       return "";
     }},
    {"camera", CommandKind::Camera, "camera EX EY EZ TX TY TZ [FOVY_DEG]", "place the camera",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 6 && a.size() != 7) return a.usage_error();
       if (auto e = a.finite_values(0, a.size(), c); !e.empty()) return e;
       c.has_fov = a.size() == 7;
       if (c.has_fov && !(c.values[6] > 1.0f && c.values[6] < 170.0f))
         return "camera: FOVY_DEG must be in (1, 170) degrees, got " + a[6];
       if (c.values[0] == c.values[3] && c.values[1] == c.values[4] && c.values[2] == c.values[5])
         return "camera: eye and target are the same point";
       return "";
     }},
    {"panel", CommandKind::Panel,
     "panel on|off | panel scene|ray|steps|code|compare|sweep|legend|vars|strip|trap on|off",
     "all panels, or one of them (`strip`: the t-axis strip)",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() == 1 && parse_on_off(a[0], &c.on)) {
         c.name = "all";
         return "";
       }
       static const char* kPanels[] = {"all",   "scene",  "ray",  "steps", "code", "compare",
                                       "sweep", "legend", "vars", "strip", "trap"};
       if (a.size() != 2 || !parse_on_off(a[1], &c.on)) return a.usage_error();
       for (const char* p : kPanels) {
         if (a[0] == p) {
           c.name = a[0];
           return "";
         }
       }
       return a.usage_error();
     }},
    {"large", CommandKind::Large, "large on|off", "lecture mode: large fonts, high contrast", parse_on_off_word},
    {"colors", CommandKind::Colors, "colors viridis|cividis|turbo [hits=blue-orange|green-red]",
     "the colour map of depths, counts and the heat map, and the hit / miss pair (defaults: viridis, blue-orange)",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       Colormap map = Colormap::Viridis;
       if (a.size() < 1 || a.size() > 2 || !parse_colormap(a[0], &map)) return a.usage_error();
       c.name = a[0];
       c.on = true;  // hits=blue-orange
       if (a.size() == 2) {
         if (a[1] == "hits=blue-orange")
           c.on = true;
         else if (a[1] == "hits=green-red")
           c.on = false;
         else
           return a.usage_error();
       }
       return "";
     }},
    {"screenshot", CommandKind::Screenshot, "screenshot PATH", "write a PNG", parse_one_word},
    {"save-state", CommandKind::SaveState, "save-state FILE",
     "write the viewer's state (scene, structure, kernel, camera, ray, step) as the script that restores it "
     "(`accelviz --restore FILE`)",
     parse_one_word},
    {"print-frame-time", CommandKind::PrintFrameTime, "print-frame-time N",
     "render N frames, print the mean frame time",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 1 || !parse_script_int(a[0], &c.ints[0]) || c.ints[0] < 1 || c.ints[0] > 10000)
         return a.usage_error() + " (1..10000 frames)";
       return "";
     }},
};

}  // namespace

std::span<const ScriptVerb> global_verbs() { return kGlobalVerbs; }

const std::vector<ScriptVerb>& script_verbs() {
  static const std::vector<ScriptVerb> all = [] {
    std::vector<ScriptVerb> v;
    for (std::span<const ScriptVerb> module :
         {global_verbs(), structure_session_verbs(), ray_debugger_verbs(), blackboard_verbs(), node_display_verbs(),
          heatmap_verbs(), compare_verbs(), sweep_verbs(), build_player_verbs(), tree_diagram_verbs(), trap_verbs(),
          playlist_verbs(), recorder_verbs(), bench_chart_verbs()})
      v.insert(v.end(), module.begin(), module.end());
    return v;
  }();
  return all;
}

std::string script_error(const std::string& script_name, int line, const std::string& message) {
  return script_name + ":" + std::to_string(line) + ": " + message;
}

accel::Result<std::vector<ScriptCommand>> parse_script(const std::string& text, const std::string& script_name) {
  std::vector<ScriptCommand> commands;
  std::vector<std::string> header;  // the comment lines above the first command
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::vector<std::string> tokens = tokens_of(line);
    if (tokens.empty()) {
      const size_t hash = line.find_first_not_of(" \t");
      if (commands.empty() && hash != std::string::npos && line[hash] == '#') {
        const size_t text_at = line.find_first_not_of(" \t", hash + 1);
        header.push_back(text_at == std::string::npos ? "" : line.substr(text_at));
      }
      continue;
    }
    const ScriptVerb* verb = find_verb(tokens[0]);
    if (!verb) return accel::make_error(script_error(script_name, number, "unknown command '" + tokens[0] + "'"));
    ScriptCommand c;
    c.line = number;
    c.kind = verb->kind;
    const std::vector<std::string> words(tokens.begin() + 1, tokens.end());
    const std::string error = verb->parse(VerbArgs(*verb, words), c);
    if (!error.empty()) return accel::make_error(script_error(script_name, number, error));
    commands.push_back(std::move(c));
  }
  bind_replays(commands, header);
  return commands;
}

accel::Result<std::vector<ScriptCommand>> load_script(const std::string& path) {
  auto text = accel::read_input_file(path, "the script");
  if (!text) return text.error();
  return parse_script(text.value(), path);
}

}  // namespace viz
