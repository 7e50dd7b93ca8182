#include "camera_control.h"

#include <imgui.h>

#include "scene.h"
#include "window_layout.h"

namespace viz {

accel::Aabb frame_box(const accel::Scene& scene) {
  accel::Aabb box = scene.bounds();
  if (scene.planar() && box.empty()) box = accel::Aabb{accel::Vec3(0.0f), accel::Vec3(10.0f, 10.0f, 0.0f)};
  return box;
}

void CameraControl::look_at(const glm::vec3& eye, const glm::vec3& target, float fovy_deg, const accel::Scene& scene) {
  camera_.look_at(eye, target, fovy_deg, scene.bounds());
  frame_requested_ = false;
}

void CameraControl::frame_now(const accel::Scene& scene, float aspect) {
  camera_.frame(frame_box(scene), aspect);
  frame_requested_ = false;
}

void CameraControl::frame_if_requested(const accel::Scene& scene, float aspect, bool settled) {
  if (frame_requested_ && settled) frame_now(scene, aspect);
}

MouseFrame CameraControl::update() {
  const ImGuiIO& io = ImGui::GetIO();
  // The mouse belongs to ImGui while it hovers a window or drags a widget; a drag that
  // started over the scene keeps going even when it crosses a panel. Click or drag is
  // judged from the press and release positions (ClickTracker), never from the deltas.
  const glm::vec2 pos(io.MousePos.x, io.MousePos.y);
  const double now = static_cast<double>(ImGui::GetTime());
  MouseFrame m;
  m.left = left_.update(io.MouseDown[ImGuiMouseButton_Left], pos, now, !io.WantCaptureMouse);
  m.right = right_.update(io.MouseDown[ImGuiMouseButton_Right], pos, now, !io.WantCaptureMouse);
  m.left_held = left_.held();
  m.left_dragging = left_.dragging();
  m.shift = io.KeyShift;
  m.scale = display_scale();
  // 2D: the left button places corners, moves them and shoots rays (the blackboard's).
  if (!camera_.top_down() && m.left.orbit != glm::vec2(0.0f)) camera_.orbit(m.left.orbit.x, m.left.orbit.y);
  if (!io.WantCaptureMouse && !left_.held() &&
      (io.MouseDown[ImGuiMouseButton_Right] || io.MouseDown[ImGuiMouseButton_Middle])) {
    // Deltas are in window coordinates, so pan with the window's height, not the
    // framebuffer's (they differ on HiDPI screens).
    camera_.pan(io.MouseDelta.x, io.MouseDelta.y, io.DisplaySize.y);
  }
  if (!io.WantCaptureMouse && io.MouseWheel != 0.0f) camera_.zoom(io.MouseWheel);
  return m;
}

}  // namespace viz
