#include "playlist.h"

#include <filesystem>
#include <sstream>

#include "commands.h"
#include "input_files.h"

namespace viz {
namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

std::string first_token(const std::string& line) {
  std::istringstream in(line);
  std::string t;
  in >> t;
  return t.empty() || t[0] == '#' ? "" : t;
}

}  // namespace

accel::Result<Playlist> parse_playlist(const std::string& text, const std::string& name) {
  Playlist playlist;
  playlist.name = name;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  // A state's command lines, padded with empty lines so parse_script numbers them as the file.
  std::string block;
  auto close_state = [&]() -> accel::Status {
    if (playlist.states.empty()) return {};
    auto commands = parse_script(block, name);
    if (!commands) return commands.error();
    playlist.states.back().commands = std::move(commands.value());
    return {};
  };
  while (std::getline(in, line)) {
    ++number;
    const std::string verb = first_token(line);
    if (verb.empty()) {
      block += '\n';
      continue;
    }
    if (verb == "state") {
      if (auto st = close_state(); !st) return st.error();
      std::string title = trim(trim(line).substr(5));
      if (const size_t hash = title.find(" #"); hash != std::string::npos) title = trim(title.substr(0, hash));
      if (title.empty()) return accel::make_error(script_error(name, number, "usage: state TITLE"));
      playlist.states.push_back({title, number, {}});
      block.assign(static_cast<size_t>(number), '\n');
      continue;
    }
    if (playlist.states.empty())
      return accel::make_error(script_error(name, number, "'" + verb + "' before the first 'state TITLE' line"));
    if (verb == "playlist" || verb == "next" || verb == "prev")
      return accel::make_error(script_error(name, number, "'" + verb + "' drives playlists; it cannot be part of a state"));
    block += line;
    block += '\n';
  }
  if (auto st = close_state(); !st) return st.error();
  if (playlist.states.empty()) return accel::make_error(name + ": no 'state TITLE' line: the playlist is empty");
  return playlist;
}

accel::Result<Playlist> load_playlist(const std::string& path) {
  auto text = accel::read_input_file(path, "the playlist");
  if (!text) return text.error();
  auto playlist = parse_playlist(text.value(), path);
  if (!playlist) return playlist;
  // Files named in a playlist are relative to the playlist, so it runs from any directory.
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(path).parent_path();
  for (PlaylistState& state : playlist.value().states)
    for (ScriptCommand& c : state.commands) {
      if (c.verb != "scene" && c.verb != "scene2d" && c.verb != "load-bench" && c.verb != "trace-rays") continue;
      std::string& name = c.get<Word>().word;  // these four take one word
      const bool names_file = (c.verb == "scene" && !name.starts_with("procedural:")) ||
                              c.verb == "scene2d" || c.verb == "load-bench" ||
                              (c.verb == "trace-rays" && !name.starts_with("random:") && !name.starts_with("primary:"));
      if (names_file && fs::path(name).is_relative()) name = (dir / name).lexically_normal().string();
    }
  return playlist;
}

std::vector<size_t> PlaylistCursor::go_to(size_t target, bool* from_scratch) {
  std::vector<size_t> apply;
  *from_scratch = false;
  if (count_ == 0) return apply;
  if (target >= count_) target = count_ - 1;
  size_t first = current_ + 1;
  if (!shown_ || target < current_) {
    *from_scratch = shown_;
    first = 0;
  } else if (target == current_) {
    return apply;  // already shown
  }
  for (size_t i = first; i <= target; ++i) apply.push_back(i);
  current_ = target;
  shown_ = true;
  return apply;
}

std::string state_line(const Playlist& playlist, size_t index) {
  if (index >= playlist.states.size()) return "no playlist";
  return "state " + std::to_string(index + 1) + "/" + std::to_string(playlist.states.size()) + ": " +
         playlist.states[index].title;
}

}  // namespace viz
