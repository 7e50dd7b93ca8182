#pragma once
// The transport of the traversal's and the construction's players, over the PlaybackClock
// both are, so the two cannot drift apart: the playback row of the "Debug ray" and
// "Construction" panels, their keys, and the step commands' moves.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

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
