#pragma once
// GL-free: a lecture playlist (`accelviz --playlist FILE`, script `playlist FILE`): an
// ordered list of states, each a titled block of script commands (script.h). A line
// `state TITLE` starts a state; the command lines after it, up to the next `state`, make it.
// A state starts from the one before it: showing state K applies states 1..K in order.
//
//   # comments and blank lines anywhere
//   state The uniform grid
//   scene procedural:cornell
//   structure grid
//   state Its 3D-DDA, mid-walk
//   preset cornell
//   step 12
#include <string>
#include <vector>

#include "result.h"
#include "script.h"

namespace viz {

struct PlaylistState {
  std::string title;
  int line = 0;                        ///< the `state` line
  std::vector<ScriptCommand> commands;  ///< in order, with their file lines
};

struct Playlist {
  std::string name;  ///< the file, as named in messages
  std::vector<PlaylistState> states;
};

/// Parses `text` (named `name` in messages). Errors are "NAME:LINE: message": a command
/// before the first state, a state without a title, a command that is not a script
/// command (validated as script.h does), a command that drives playlists inside a state
/// (playlist, next, prev), or no state at all.
accel::Result<Playlist> parse_playlist(const std::string& text, const std::string& name);
/// Reads and parses a playlist file; the error names the file when it cannot be read.
/// Scene files and bench JSON files named with a relative path are relative to the playlist.
accel::Result<Playlist> load_playlist(const std::string& path);

/// Which state is shown and how to get from one to another.
class PlaylistCursor {
 public:
  void reset(size_t count) {
    count_ = count;
    current_ = 0;
  }
  size_t size() const { return count_; }
  /// 0-based index of the state shown.
  size_t current() const { return current_; }
  /// The states to apply, in order, to show state `target` (clamped) from the current one:
  /// forward only the new ones; backward all from the first (a state starts from the one
  /// before it, so going back replays). `from_scratch` says whether the viewer must reset
  /// first. Makes `target` the current state.
  std::vector<size_t> go_to(size_t target, bool* from_scratch);

 private:
  size_t count_ = 0;
  size_t current_ = 0;
  bool shown_ = false;  // a state has been applied since reset()
};

/// "state K/N: TITLE" (print-state), K 1-based.
std::string state_line(const Playlist& playlist, size_t index);

}  // namespace viz
