#include "camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace viz {
namespace {

constexpr float kOrbitRadiansPerPixel = 0.005f;
constexpr float kZoomFactorPerStep = 0.88f;
// Just short of straight up/down: at exactly +-90 degrees lookAt's up vector degenerates.
constexpr float kMaxPitch = 1.55f;

}  // namespace

void Camera::frame(const accel::Aabb& bounds, float aspect) {
  accel::Aabb box = bounds;
  if (box.empty()) {
    box.min = glm::vec3(-0.5f);
    box.max = glm::vec3(0.5f);
  }
  target_ = box.center();
  // A flat or point-like scene still needs a positive radius for zoom and clip limits.
  scene_radius_ = std::max(0.5f * glm::length(box.extent()), 1e-4f);
  if (top_down_) {
    // The plane's box fills the view with the same 8% margin; the eye well above it.
    const glm::vec3 e = box.extent();
    half_height_ = std::max({0.5f * e.y, 0.5f * e.x / std::max(aspect, 1e-3f), 1e-4f}) * 1.08f;
    target_.z = 0.0f;
    distance_ = 2.0f * scene_radius_ + 1.0f;
    return;
  }
  yaw_ = kDefaultYaw;
  pitch_ = kDefaultPitch;

  // Fitting the bounding sphere wastes most of the screen on flat scenes (a stadium, a
  // floor plan); fit the corners instead. A corner at offset (x, y, z) in the camera's
  // right/up/forward frame is visible when |y| <= (d + z) tan(fov_y / 2), likewise for x
  // with the horizontal half-angle: solve each for the distance d and take the largest.
  const float tan_y = std::tan(0.5f * fov_y_);
  const float tan_x = tan_y * std::max(aspect, 1e-3f);
  const glm::vec3 f = forward();
  const glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, f);
  float distance = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                           (i & 4) ? box.max.z : box.min.z);
    const glm::vec3 offset = corner - target_;
    const float z = glm::dot(offset, f);
    distance = std::max(distance, std::abs(glm::dot(offset, right)) / tan_x - z);
    distance = std::max(distance, std::abs(glm::dot(offset, up)) / tan_y - z);
  }
  // 8% margin so the box's outline does not touch the window edge; never inside the box.
  distance_ = std::max(distance * 1.08f, scene_radius_ * 0.1f);
}

void Camera::orbit(float dx, float dy) {
  if (top_down_) return;
  yaw_ -= dx * kOrbitRadiansPerPixel;
  pitch_ = std::clamp(pitch_ - dy * kOrbitRadiansPerPixel, -kMaxPitch, kMaxPitch);
}

void Camera::pan(float dx, float dy, float viewport_height) {
  if (top_down_) {
    target_ += glm::vec3(-dx, dy, 0.0f) * units_per_pixel(viewport_height);
    return;
  }
  // World units per pixel at the target's depth, so the grabbed point stays under the cursor.
  const float units_per_pixel =
      2.0f * distance_ * std::tan(0.5f * fov_y_) / std::max(viewport_height, 1.0f);
  const glm::vec3 f = forward();
  const glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, f);
  target_ += (-dx * right + dy * up) * units_per_pixel;
}

void Camera::zoom(float steps) {
  if (top_down_) {
    half_height_ = std::clamp(half_height_ * std::pow(kZoomFactorPerStep, steps), scene_radius_ * 1e-3f,
                              scene_radius_ * 1e3f);
    return;
  }
  distance_ *= std::pow(kZoomFactorPerStep, steps);
  // Never through the target, and not so far that the scene becomes a dot.
  distance_ = std::clamp(distance_, scene_radius_ * 1e-3f, scene_radius_ * 1e3f);
}

void Camera::look_at(const glm::vec3& eye, const glm::vec3& target, float fovy_deg, const accel::Aabb& scene_bounds) {
  const glm::vec3 offset = target - eye;
  const float distance = glm::length(offset);
  if (!(distance > 0.0f)) return;
  const glm::vec3 f = offset / distance;
  target_ = target;
  distance_ = distance;
  // forward() = (cos p * -sin y, sin p, cos p * -cos y), inverted.
  pitch_ = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
  yaw_ = std::atan2(-f.x, -f.z);
  fov_y_ = glm::radians(std::clamp(fovy_deg, 1.0f, 170.0f));
  if (!scene_bounds.empty()) scene_radius_ = std::max(0.5f * glm::length(scene_bounds.extent()), 1e-4f);
}

accel::PinholeCamera Camera::pinhole() const {
  accel::PinholeCamera cam;
  cam.eye = eye();
  cam.target = target_;
  cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
  cam.fovy_deg = glm::degrees(fov_y_);
  // Top-down: the pinhole above the target whose view of the plane z = 0 is exactly the
  // orthographic one (the same half height at the plane's distance), so the heat map's rays
  // land on the points drawn under their pixels: each costs what locating that point does.
  if (top_down_) cam.fovy_deg = glm::degrees(2.0f * std::atan(half_height_ / distance_));
  return cam;
}

glm::vec3 Camera::project(const glm::vec3& p, int width, int height) const {
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  const glm::vec4 clip = projection(aspect) * view() * glm::vec4(p, 1.0f);
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * static_cast<float>(width), (0.5f - ndc.y * 0.5f) * static_cast<float>(height),
          ndc.z};
}

glm::vec3 Camera::plane_point(float px, float py, int width, int height) const {
  const float upp = units_per_pixel(static_cast<float>(height));
  return {target_.x + (px - 0.5f * static_cast<float>(width)) * upp,
          target_.y + (0.5f * static_cast<float>(height) - py) * upp, 0.0f};
}

glm::vec3 Camera::forward() const {
  if (top_down_) return {0.0f, 0.0f, -1.0f};
  return {std::cos(pitch_) * -std::sin(yaw_), std::sin(pitch_), std::cos(pitch_) * -std::cos(yaw_)};
}

glm::vec3 Camera::eye() const { return target_ - distance_ * forward(); }

glm::mat4 Camera::view() const { return glm::lookAt(eye(), target_, glm::vec3(0, 1, 0)); }
// (Top-down, forward() is -Z: the eye straight above the target, +Y up on the screen.)

glm::mat4 Camera::projection(float aspect) const {
  // Near and far bracket the scene's bounding sphere around the target, with slack for
  // panning; a near plane proportional to the distance keeps the depth ratio bounded.
  const float far_plane = distance_ + 4.0f * scene_radius_;
  const float near_plane = std::max(far_plane * 1e-4f, distance_ - 4.0f * scene_radius_);
  if (top_down_) {
    const float half_width = half_height_ * std::max(aspect, 1e-3f);
    return glm::ortho(-half_width, half_width, -half_height_, half_height_, std::max(near_plane, 1e-6f), far_plane);
  }
  return glm::perspective(fov_y_, std::max(aspect, 1e-3f), std::max(near_plane, 1e-6f), far_plane);
}

}  // namespace viz
