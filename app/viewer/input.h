#pragma once
// GL-free judgement of the left mouse button: click (shoot a ray) or drag (orbit); on the
// blackboard (2D mode) tools/blackboard_editor.h gives them their 2D meaning. Owns only the
// press position and time; App feeds it the button, cursor and clock per frame. Also what
// the mouse does, in words, per mode: the one source of the help's mouse lines, the docs'
// mouse table (`accelviz --list mouse`) and the panels' "shoot a ray" hints.
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace viz {

/// What one mouse action does in the 3D view and on the blackboard (2D mode); "" where it
/// does nothing in that mode.
struct MouseRow {
  const char* mouse = "";  ///< "left drag"
  const char* in_3d = "";  ///< "orbit the camera"
  const char* in_2d = "";  ///< "on a corner: move it; elsewhere: shoot the debug ray along the drag"
};

/// Every mouse action, as App::update_camera_input, App::update_board_input and
/// BlackboardEditor bind them.
std::span<const MouseRow> mouse_rows();
/// The help's lines for one mode, "MOUSE: what it does" (the blackboard's when `board`);
/// the actions that do nothing there are left out.
std::vector<std::string> mouse_help_lines(bool board);
/// How the debug ray is shot in this mode, for the panels still waiting for one: a click
/// into the 3D view, a drag on the blackboard.
const char* shoot_hint(bool board);

/// What one frame of left-button input means.
struct ClickResult {
  bool click = false;           ///< released as a click this frame: shoot through press_pos
  glm::vec2 press_pos{0.0f};    ///< where the button went down (window coordinates)
  glm::vec2 orbit{0.0f};        ///< pixels to orbit by this frame (zero unless dragging)
  bool drag_end = false;        ///< a drag ended this frame (released at `pos`)
  glm::vec2 pos{0.0f};          ///< the cursor this frame, while held or at the release
};

/// Tells a click from a drag by positions and time, never by mouse deltas: on a slow frame
/// the movement before the press arrives in the press frame, and must not count.
class ClickTracker {
 public:
  /// Farther than this from the press position (pixels) makes a drag.
  static constexpr float kTolerance = 4.0f;
  /// A press held longer than this (seconds) before its release is no click. Generous,
  /// since at 2 fps press and release already land half a second apart.
  static constexpr double kMaxClickSeconds = 1.0;

  /// One frame: whether the button is down, the cursor position, the time in seconds, and
  /// whether a press seen now may start a click or drag (false over a panel).
  ClickResult update(bool down, glm::vec2 pos, double time, bool press_allowed);

  /// The button went down in the 3D view and is still held.
  bool held() const { return held_; }
  /// The held button has moved beyond kTolerance: orbiting.
  bool dragging() const { return dragging_; }

 private:
  bool was_down_ = false;
  bool held_ = false;
  bool dragging_ = false;
  glm::vec2 press_pos_{0.0f};
  glm::vec2 last_pos_{0.0f};
  double press_time_ = 0.0;
};

}  // namespace viz
