#include "script.h"

#include <cstdio>
#include <sstream>

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
  StructureArgs* structure = nullptr;
  for (ScriptCommand& c : commands) {
    if (c.verb == "structure") structure = &c.get<StructureArgs>();
    if (c.verb != "construct-until") continue;
    ConstructUntilArgs& until = c.get<ConstructUntilArgs>();
    if (structure && structure->calls == 0) structure->calls = until.calls;
    if (from_check) until.header = header;
  }
}

}  // namespace

const VerbTable& script_verbs() {
  static const VerbTable catalogue = [] {
    VerbTable table;
    VerbCatalogue verbs(table);
    global_verbs(verbs);
    structure_session_verbs(verbs);
    ray_debugger_verbs(verbs);
    blackboard_verbs(verbs);
    node_display_verbs(verbs);
    heatmap_verbs(verbs);
    compare_verbs(verbs);
    sweep_verbs(verbs);
    build_player_verbs(verbs);
    tree_diagram_verbs(verbs);
    trap_verbs(verbs);
    playlist_verbs(verbs);
    recorder_verbs(verbs);
    bench_chart_verbs(verbs);
    return table;
  }();
  return catalogue;
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
    const Verb* verb = script_verbs().find(tokens[0]);
    if (!verb) return accel::make_error(script_error(script_name, number, "unknown command '" + tokens[0] + "'"));
    ScriptCommand c;
    c.verb = verb->name;
    c.line = number;
    const std::vector<std::string> words(tokens.begin() + 1, tokens.end());
    const std::string error = verb->parse(VerbArgs(*verb, words), c.args);
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
