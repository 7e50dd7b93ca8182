#include "input.h"

namespace viz {

ClickResult ClickTracker::update(bool down, glm::vec2 pos, double time, bool press_allowed) {
  ClickResult r;
  const bool pressed = down && !was_down_;
  const bool released = !down && was_down_;
  was_down_ = down;
  if (pressed && press_allowed) {
    // The press position is where the cursor is now; whatever moved it there before the
    // press (this frame's delta) is not part of a drag.
    held_ = true;
    dragging_ = false;
    press_pos_ = pos;
    last_pos_ = pos;
    press_time_ = time;
    return r;
  }
  if (!held_) return r;
  r.press_pos = press_pos_;
  r.pos = pos;
  if (down) {
    if (!dragging_ && glm::length(pos - press_pos_) > kTolerance) {
      dragging_ = true;
      r.orbit = pos - press_pos_;  // the whole way from the press: no jump, nothing lost
    } else if (dragging_) {
      r.orbit = pos - last_pos_;
    }
    last_pos_ = pos;
    return r;
  }
  if (released) {
    r.click = !dragging_ && glm::length(pos - press_pos_) <= kTolerance && time - press_time_ <= kMaxClickSeconds;
    r.drag_end = dragging_;
    held_ = false;
    dragging_ = false;
  }
  return r;
}

}  // namespace viz
