#include "input.h"

namespace viz {

std::span<const MouseRow> mouse_rows() {
  static const MouseRow kRows[] = {
      {"left drag", "orbit the camera",
       "from a corner: move it (the structure is rebuilt as it moves); elsewhere: shoot the debug ray from where the "
       "drag starts, along the drag"},
      {"left click", "shoot the debug ray through that pixel",
       "place a triangle's corner; the third adds the triangle (Esc forgets the corners)"},
      {"shift + left click",
       "shoot from the saved viewpoint (Scene > Save view) at the point under the cursor; 'from saved view' in the "
       "Debug ray panel makes every click do this",
       "as a left click"},
      {"right click", "", "delete the triangle under the cursor"},
      {"right or middle drag", "pan", "pan"},
      {"wheel", "zoom", "zoom"},
      {"in the tree diagram: click, wheel, drag", "select a node; zoom; pan", "select a node; zoom; pan"},
  };
  return kRows;
}

std::vector<std::string> mouse_help_lines(bool board) {
  std::vector<std::string> lines;
  for (const MouseRow& row : mouse_rows()) {
    const std::string what = board ? row.in_2d : row.in_3d;
    if (!what.empty()) lines.push_back(std::string(row.mouse) + ": " + what);
  }
  return lines;
}

const char* shoot_hint(bool board) {
  return board ? "drag on the board to shoot a ray along the drag" : "click into the scene to shoot a ray through that pixel";
}

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
