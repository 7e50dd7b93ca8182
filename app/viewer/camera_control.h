#pragma once
// The 3D view's camera and the mouse over it (issue #50: out of App): orbit, pan and zoom,
// click or drag judged by ClickTracker (input.h), and when to frame the scene (after the
// panels are placed, so it fits the view they leave). Clicks go to the tools (Tool::mouse):
// a click into the 3D view shoots the debug ray, the blackboard takes its own.
#include <glm/glm.hpp>

#include "camera.h"
#include "geometry.h"
#include "input.h"

namespace accel {
class Scene;
}

namespace viz {

/// One frame of the mouse over the 3D view, for the tools.
struct MouseFrame {
  ClickResult left, right;  ///< the buttons' clicks and drags (window coordinates)
  bool left_held = false;   ///< the left button went down in the view and is held
  bool left_dragging = false;
  bool shift = false;
  glm::vec2 scale{1.0f};    ///< framebuffer pixels per window unit
};

class CameraControl {
 public:
  Camera& camera() { return camera_; }
  const Camera& camera() const { return camera_; }
  accel::PinholeCamera pinhole() const { return camera_.pinhole(); }

  /// Frames the scene at the next draw that has the panels placed.
  void request_frame() { frame_requested_ = true; }
  /// Places the camera (a script's `camera`, a preset, the saved view); no framing follows.
  void look_at(const glm::vec3& eye, const glm::vec3& target, float fovy_deg, const accel::Scene& scene);
  /// Frames `scene` into a view of `aspect` now.
  void frame_now(const accel::Scene& scene, float aspect);
  /// Frames `scene` when framing is due and the layout is `settled` (or the panels hidden).
  void frame_if_requested(const accel::Scene& scene, float aspect, bool settled);

  /// One frame of the mouse (ImGui's input; nothing reaches the view over a panel): orbits
  /// on a left drag in 3D, pans on a right or middle drag, zooms on the wheel, and returns
  /// the clicks for the tools.
  MouseFrame update();

 private:
  Camera camera_;
  bool frame_requested_ = true;
  ClickTracker left_;
  ClickTracker right_;  // 2D: a right click deletes a triangle (a right drag pans)
};

/// What the camera frames: the scene's box, or a 10 x 10 board for an empty 2D scene.
accel::Aabb frame_box(const accel::Scene& scene);

}  // namespace viz
