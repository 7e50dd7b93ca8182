#pragma once
// Orbit camera: a target point, a distance, and yaw/pitch angles around it, Y up. In the
// blackboard's 2D mode (set_top_down) it looks straight down -Z at the plane z = 0 with an
// orthographic projection, +X right and +Y up: orbiting is off, pan and zoom move and scale
// the window onto the plane.
// It knows no GLFW or ImGui; App feeds it mouse deltas only while ImGui does not want
// the mouse (io.WantCaptureMouse), so dragging a slider never spins the scene.
#include <algorithm>

#include <glm/glm.hpp>

#include "vec_math.h"
#include "ray_gen.h"

namespace viz {

/// Perspective orbit camera with Y up.
class Camera {
 public:
  /// Looks at the box from the front and above, at the smallest distance at which all
  /// eight corners fit a viewport of the given aspect ratio (width / height), with a small
  /// margin. An empty box frames the unit cube.
  void frame(const accel::Aabb& bounds, float aspect);

  /// The 2D mode's top-down orthographic view (true), or the perspective orbit (false).
  void set_top_down(bool on) { top_down_ = on; }
  bool top_down() const { return top_down_; }
  /// Top-down: the point of the plane z = 0 under framebuffer pixel (px, py) (from the
  /// top-left) of a width x height view; z = 0.
  glm::vec3 plane_point(float px, float py, int width, int height) const;
  /// Top-down: world units per pixel of a view `height` pixels tall.
  float units_per_pixel(float height) const { return 2.0f * half_height_ / std::max(height, 1.0f); }

  /// Rotates around the target; dx/dy are pixels dragged (right/down positive). Not top-down.
  void orbit(float dx, float dy);
  /// Moves the target in the view plane so the point under the cursor follows it;
  /// dx/dy are pixels dragged, `viewport_height` the framebuffer height in pixels.
  void pan(float dx, float dy, float viewport_height);
  /// Moves towards the target by `steps` wheel notches (positive = closer).
  void zoom(float steps);

  /// Looks from `eye` at `target` with a vertical field of view of `fovy_deg` degrees (a
  /// preset's or a script's saved view). The pitch is limited to just short of straight up
  /// or down, as when orbiting; `scene_bounds` sets the clip range as frame() does.
  void look_at(const glm::vec3& eye, const glm::vec3& target, float fovy_deg, const accel::Aabb& scene_bounds);

  /// The camera as the core's pinhole model (eye, target, up = +Y, vertical field of view).
  /// accel::camera_ray(pinhole(), px, py, width, height) is the ray through framebuffer pixel
  /// (px, py) from the top-left of exactly what view() and projection() draw, so picking,
  /// the heat map and the rendered image agree. Top-down: the pinhole that sees the plane
  /// z = 0 as the orthographic view draws it (rays onto the plane, for the heat map).
  accel::PinholeCamera pinhole() const;

  /// Framebuffer position (from the top-left, pixels) of world point `p` in a viewport of
  /// width x height; z is the point's NDC depth. For tests of the picking round trip.
  glm::vec3 project(const glm::vec3& p, int width, int height) const;

  /// World-to-view matrix.
  glm::mat4 view() const;
  /// View-to-clip matrix for a viewport of the given aspect ratio (width / height).
  /// Near and far planes follow the distance and the framed scene size, so depth precision
  /// holds for both tiny and huge scenes.
  glm::mat4 projection(float aspect) const;
  /// Eye position in world space.
  glm::vec3 eye() const;
  glm::vec3 target() const { return target_; }
  float distance() const { return distance_; }
  /// Vertical field of view in radians.
  float fov_y() const { return fov_y_; }

 private:
  // Front-right and about 30 degrees above: shows top and two sides of a box-like scene.
  static constexpr float kDefaultYaw = 0.6f;
  static constexpr float kDefaultPitch = -0.5f;

  glm::vec3 forward() const;  // unit vector from the eye to the target

  glm::vec3 target_{0.0f};
  float distance_ = 3.0f;
  float yaw_ = kDefaultYaw;      // radians around +Y; 0 looks down -Z
  float pitch_ = kDefaultPitch;  // radians; negative looks down on the scene
  float fov_y_ = glm::radians(45.0f);
  float scene_radius_ = 1.0f;  // of the last framed box; sets the near/far range
  bool top_down_ = false;
  float half_height_ = 1.0f;  // top-down: half the view's height in world units
};

}  // namespace viz
