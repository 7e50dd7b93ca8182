// App, part 4: the blackboard (2D mode, issue #32). A 2D scene (triangles in the plane
// z = 0, docs/hits.md) is shown from above by the camera's top-down orthographic view and
// built and traversed by the very structures of the 3D mode; this file switches the mode,
// edits the scene (script commands and the mouse: BlackboardEditor) and draws the board's
// grid of world units.
#include <cmath>

#include <imgui.h>

#include "app.h"
#include "planar_geometry.h"
#include "scene2d.h"

namespace viz {

accel::Status App::set_mode_2d(bool on) {
  if (on == mode_2d()) return {};
  if (!on) return load_scene(last_3d_scene_);
  // An empty board; the structure is rebuilt over it like over any scene.
  accel::Scene board;
  (void)board.mark_planar();  // no vertex: always succeeds
  session_.set_scene(std::move(board), "blackboard", false);
  sync_session();
  return loaded();
}

accel::Status App::load_scene2d(const std::string& path) {
  auto scene = accel::load_scene2d(path);
  if (!scene) return scene.error();
  session_.set_scene(std::move(scene.value()), path, false);
  sync_session();
  return loaded();
}

accel::Status App::add_triangle_2d(const std::array<float, 6>& xy) {
  if (!mode_2d()) return accel::make_error("add2d: not in 2D mode (mode 2d first)");
  const SceneInfo& info = session_.scene_info();
  session_.set_scene(accel::scene2d_with_triangle(session_.scene(), xy), info.spec, true);
  sync_session();
  return loaded();
}

accel::Status App::set_ray_2d(float ox, float oy, float dx, float dy) {
  if (!mode_2d()) return accel::make_error("ray2d: not in 2D mode (mode 2d first)");
  accel::Ray r;
  r.org = {ox, oy, 0.0f};
  r.dir = {dx, dy, 0.0f};
  set_ray(r, "2D ray");
  return {};
}

void App::update_board_input(const ClickResult& r) {
  const ImGuiIO& io = ImGui::GetIO();
  const float sx = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
  const float sy = io.DisplayFramebufferScale.y > 0.0f ? io.DisplayFramebufferScale.y : 1.0f;
  // Window coordinates -> framebuffer pixels -> the 3D view's pixels -> the plane.
  auto plane = [&](glm::vec2 window) {
    const glm::vec3 p = camera_.plane_point(window.x * sx - static_cast<float>(view_.x),
                                            window.y * sy - static_cast<float>(view_.y), view_.z, view_.w);
    return glm::vec2(p.x, p.y);
  };
  const BlackboardAction a = board_.update(r, plane(r.press_pos), plane(r.pos), click_.dragging());
  if (a.kind == BlackboardAction::Kind::AddTriangle) (void)add_triangle_2d(a.triangle);
  if (a.kind == BlackboardAction::Kind::ShootRay) set_ray(a.ray, "dragged 2D ray");
}

accel::Aabb App::frame_box() const {
  accel::Aabb box = session_.scene().bounds();
  if (mode_2d() && box.empty()) box = accel::Aabb{accel::Vec3(0.0f), accel::Vec3(10.0f, 10.0f, 0.0f)};
  return box;
}

void App::draw_board(bool grid) {
  if (!mode_2d() || !board_lines_) return;
  std::vector<ColorVertex> lines;
  auto line = [&](glm::vec2 a, glm::vec2 b, glm::vec4 c) {
    lines.push_back({glm::vec3(a, 0.0f), c});
    lines.push_back({glm::vec3(b, 0.0f), c});
  };
  const float upp = camera_.units_per_pixel(static_cast<float>(view_.w));
  if (grid) {
    // The grid of world units over the visible part of the plane, every fifth line brighter.
    const glm::vec3 lo = camera_.plane_point(0.0f, static_cast<float>(view_.w), view_.z, view_.w);
    const glm::vec3 hi = camera_.plane_point(static_cast<float>(view_.z), 0.0f, view_.z, view_.w);
    const float step = grid_spacing(upp, 24.0f);
    const glm::vec4 faint(0.35f, 0.40f, 0.48f, 0.35f), strong(0.50f, 0.56f, 0.66f, 0.6f);
    for (long k = std::lround(std::floor(lo.x / step)); static_cast<float>(k) * step <= hi.x; ++k)
      line({static_cast<float>(k) * step, lo.y}, {static_cast<float>(k) * step, hi.y}, k % 5 == 0 ? strong : faint);
    for (long k = std::lround(std::floor(lo.y / step)); static_cast<float>(k) * step <= hi.y; ++k)
      line({lo.x, static_cast<float>(k) * step}, {hi.x, static_cast<float>(k) * step}, k % 5 == 0 ? strong : faint);
  } else {
    // The corners placed so far (a cross each, joined), and the ray being dragged.
    const float r = 6.0f * upp;
    const glm::vec4 yellow(1.0f, 0.85f, 0.2f, 1.0f);
    const std::vector<glm::vec2>& corners = board_.pending();
    for (size_t k = 0; k < corners.size(); ++k) {
      line(corners[k] - glm::vec2(r, 0), corners[k] + glm::vec2(r, 0), yellow);
      line(corners[k] - glm::vec2(0, r), corners[k] + glm::vec2(0, r), yellow);
      if (k > 0) line(corners[k - 1], corners[k], yellow);
    }
    if (auto drag = board_.drag_line()) line(drag->first, drag->second, yellow);
  }
  if (lines.empty()) return;
  board_lines_->upload(lines, GL_DYNAMIC_DRAW);
  LineStyle style;
  style.depth_test = false;
  renderer_->draw_lines(*board_lines_, style);
}

}  // namespace viz
