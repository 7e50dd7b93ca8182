#pragma once
// The blackboard's editing (2D mode, issue #32), GL-free: what a click or a drag in the
// plane means. Clicks place a triangle's corners one by one and the third adds the triangle;
// a drag that starts on a corner moves it; any other drag shoots the debug ray from where it
// started along the drag. App applies the actions (a new scene, a new ray) and draws what is
// pending.
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "input.h"
#include "vec_math.h"

namespace viz {

/// What the user did on the blackboard this frame.
struct BlackboardAction {
  enum class Kind { None, AddTriangle, ShootRay, MoveVertex };
  Kind kind = Kind::None;
  std::array<float, 6> triangle{};  ///< AddTriangle: x1 y1 x2 y2 x3 y3
  accel::Ray ray;                   ///< ShootRay: a 2D ray (z = 0), direction = the drag
  int vertex = -1;                  ///< MoveVertex: the scene's vertex index ...
  glm::vec2 position{0.0f};         ///< ... and where it goes
};

class BlackboardEditor {
 public:
  /// One frame of left-button input (`r`, from ClickTracker) with the plane points (z = 0)
  /// under its press position and under the cursor, whether the button is dragging, and the
  /// scene's vertex at the press point (-1: none), which a drag starting there moves.
  BlackboardAction update(const ClickResult& r, glm::vec2 press_point, glm::vec2 point, bool dragging,
                          int vertex_at_press = -1);
  /// The corners placed so far (0, 1 or 2).
  const std::vector<glm::vec2>& pending() const { return pending_; }
  /// While a drag is under way: from its start to the cursor (the ray to be shot).
  std::optional<std::pair<glm::vec2, glm::vec2>> drag_line() const { return drag_; }
  /// Forgets the corners placed (a new scene, Escape).
  void clear() { pending_.clear(); }

 private:
  std::vector<glm::vec2> pending_;
  std::optional<std::pair<glm::vec2, glm::vec2>> drag_;
  int moving_ = -1;  // the vertex being dragged
};

/// The spacing of the blackboard's grid lines: the smallest of 1, 2 and 5 times a power of
/// ten world units that is at least `min_pixels` apart at `units_per_pixel`.
float grid_spacing(float units_per_pixel, float min_pixels);

}  // namespace viz
