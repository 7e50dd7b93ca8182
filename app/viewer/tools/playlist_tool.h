#pragma once
// The lecture playlist (playlist.h) in the viewer: which state is shown, the commands still
// to run to reach the one asked for, the title overlay, and the "Playlist" section. App
// runs the commands (the same App::execute a script uses): in script mode all at once, in
// the window one per frame and only while no build is running, so the window stays live
// while a state loads.
#include <deque>
#include <optional>
#include <string>

#include "commands.h"
#include "playlist.h"
#include "result.h"
#include "tool_host.h"
#include "tools/tool.h"
#include "view_layout.h"

namespace viz {

class PlaylistTool final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "playlist"; }
  /// PgDn / PgUp and down / up while a playlist is loaded (a presenter's clicker); `host`
  /// moves between states.
  std::vector<KeyBinding> keys(ToolHost& host) override;
  /// playlist, next, prev, print-state.
  void add_verbs(VerbTable& table, ToolHost& host) override;
  /// In the window: the queued commands of the state, one per frame.
  void update(ToolHost& host, float dt) override;
  /// Own: the "Playlist" section (open while one is loaded).
  void section(ToolHost& host, PanelSection section) override;
  /// The state's title at the top of the view, with or without the panels.
  void overlay(ToolHost& host) override;
  /// " - state K/N: TITLE", and whether it is loading or failed.
  void window_title(std::string& title, const ToolHost& host) const override;

  /// Loads `path` (errors "FILE:LINE: ..."); the previous playlist stays on failure.
  /// Does not show a state yet: go() does.
  accel::Status load(const std::string& path);
  bool loaded() const { return !playlist_.states.empty(); }
  const Playlist& playlist() const { return playlist_; }
  size_t current() const { return cursor_.current(); }

  /// Moves to state `index` (clamped): queues the
  /// commands of the states to apply. Returns true when the viewer must be reset first
  /// (going back replays from the first state).
  bool go(size_t index);
  /// The states after and before the current one (go() clamps past the last; the first
  /// has none before it).
  size_t next_index() const { return cursor_.current() + 1; }
  size_t prev_index() const { return cursor_.current() > 0 ? cursor_.current() - 1 : 0; }

  /// The commands still to run (front first), each with the state it belongs to.
  struct Pending {
    size_t state;
    const ScriptCommand* command;
  };
  bool has_pending() const { return !pending_.empty(); }
  Pending front() const { return pending_.front(); }
  void pop() { pending_.pop_front(); }
  /// A command failed: the rest of the state is dropped; the error is shown.
  void fail(const std::string& message);

  /// The error of the last state run ("FILE:LINE: message"), empty if none.
  const std::string& error() const { return error_; }
  /// "state K/N: TITLE" (print-state).
  std::string state_line() const { return viz::state_line(playlist_, cursor_.current()); }

  /// The title overlay, for a few seconds after a move (at the top centre of `view`, window
  /// coordinates x, y, w, h), and the last error until the next move.
  void title_overlay(glm::vec4 view, double now);
  /// The main panel's "Playlist" section: previous / next and the list; returns the state
  /// clicked, if any.
  std::optional<size_t> states_section();

 private:
  Playlist playlist_;
  PlaylistCursor cursor_;
  std::deque<Pending> pending_;
  double shown_at_ = -1.0;  // ImGui time the title appeared (-1: not yet, set at the first overlay)
  std::string error_;
};

}  // namespace viz
