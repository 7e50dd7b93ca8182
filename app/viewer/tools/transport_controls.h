#pragma once
// The transport of the traversal's and the construction's players, over the PlaybackClock
// both are, so the two cannot drift apart: the playback row of the "Debug ray" and
// "Construction" panels, the steps list of their steps panels, their keys, and the step
// commands' moves.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "commands.h"
#include "playback_clock.h"
#include "script.h"

namespace viz {

/// How a player numbers its steps on the slider.
struct TransportNumbers {
  /// The number shown for step 0: 1 for a traversal ("step 1 of N": the first event has
  /// happened), 0 for a construction ("step 0 of N": nothing built yet).
  size_t first = 0;
  /// The slider's text when there is nothing to play.
  const char* empty_text = "nothing recorded";
};

/// |< < Play/Pause > >| (then `more_buttons`, on the same line), and below them the step
/// and speed sliders side by side; all disabled while the clock is empty. Every control
/// but Play/Pause pauses first, so the step stays where it was put.
void transport_controls(accel::PlaybackClock& clock, const TransportNumbers& numbers,
                        const std::function<void()>& more_buttons = {});

/// One row of a steps list.
struct StepRow {
  int depth = 0;     ///< indentation: the node's depth (at most 24 shown)
  std::string text;  ///< what happened at the step
  ImVec4 color;      ///< its colour (the current row is black on the highlight instead)
};

/// A steps list's state: whether it follows the player, and the row it last scrolled to.
struct StepListState {
  bool follow = true;
  size_t scrolled = ~size_t(0);
};

/// The body of a steps panel: the "follow" box, a hint, and a scrolling list of `rows`
/// numbered rows (only the visible ones made, by `row`). Row `current` (none: no step yet)
/// is highlighted; while following, the list scrolls row `scroll_to` to the middle whenever
/// it changes. Returns the row clicked (the caller moves its player there and sets
/// state.scrolled, so the list stays where the click was).
std::optional<size_t> step_list(size_t rows, std::optional<size_t> current, size_t scroll_to, StepListState& state,
                                const std::function<StepRow(size_t)>& row);

/// A player's transport keys: GLFW keys and the help's names for them.
struct TransportKeys {
  const char* noun = "";  ///< what plays: "traversal", "construction"
  int play = 0;
  const char* play_label = "";
  int back = 0, forward = 0;
  const char* step_label = "";
  int first = 0, last = 0;
  const char* ends_label = "";
  int slower = 0, faster = 0;
  const char* speed_label = "";
  const char* ends_note = "";  ///< appended to the first / last step's help
};

/// The rows of `keys` over `clock`: play / pause, one step back / forward (shift: 10),
/// first / last step, slower / faster (by 1.5). All but play / pause pause first.
std::vector<KeyBinding> transport_keys(accel::PlaybackClock& clock, const TransportKeys& keys);

/// Moves `clock` as a `step` / `build-step` command says: `count` steps forward or back, to
/// the end or the start (StepMode::Hit is the player's own; here it is the start).
void step_clock(accel::PlaybackClock& clock, StepMode mode, size_t count);

}  // namespace viz
