#pragma once
// The playback row of the "Debug ray" and "Construction" panels: one widget over the
// PlaybackClock both players are, so the two rows cannot drift apart.
#include <cstddef>
#include <functional>

#include "playback_clock.h"

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

}  // namespace viz
