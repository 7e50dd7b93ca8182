// App, part 4: the blackboard (2D mode, issue #32). A 2D scene (triangles in the plane
// z = 0, docs/hits.md) is shown from above by the camera's top-down orthographic view and
// built and traversed by the very structures of the 3D mode; this file switches the mode,
// edits the scene (its script verbs, registered in tools/blackboard_verbs.h, and the
// mouse: BlackboardEditor) and draws the board's grid of world units.
#include <cmath>

#include <imgui.h>
#include <imgui_stdlib.h>

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

accel::Status App::save_scene2d(const std::string& path) {
  if (!mode_2d()) return accel::make_error("save2d: not in 2D mode (mode 2d first)");
  return accel::save_scene2d(path, session_.scene());
}

void App::board_section() {
  bool board = mode_2d();
  if (ImGui::Checkbox("blackboard: 2D mode (D)", &board)) (void)set_mode_2d(board);  // errors show below
  if (ImGui::IsItemHovered()) {
    // What the mouse does there, from its rows (input.h): one source for the help too.
    std::string tip = "triangles in a plane seen from above; the mouse there:";
    for (const std::string& line : mouse_help_lines(true)) tip += "\n  " + line;
    ImGui::SetTooltip("%s", tip.c_str());
  }
  if (!board) return;
  ImGui::SetNextItemWidth(12.0f * ImGui::GetFontSize());
  ImGui::InputText("##board_path", &board_path_);
  ImGui::SameLine();
  if (ImGui::Button("Save 2D scene")) {
    const accel::Status saved = save_scene2d(board_path_);
    board_status_ = saved ? "saved " + board_path_ : saved.error().message;
  }
  if (!board_status_.empty()) ImGui::TextWrapped("%s", board_status_.c_str());
}

void App::update_board_input(const ClickResult& r, const ClickResult& right) {
  const ImGuiIO& io = ImGui::GetIO();
  const float sx = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
  const float sy = io.DisplayFramebufferScale.y > 0.0f ? io.DisplayFramebufferScale.y : 1.0f;
  // Window coordinates -> framebuffer pixels -> the 3D view's pixels -> the plane.
  auto plane = [&](glm::vec2 window) {
    const glm::vec3 p = camera_.plane_point(window.x * sx - static_cast<float>(view_.x),
                                            window.y * sy - static_cast<float>(view_.y), view_.z, view_.w);
    return glm::vec2(p.x, p.y);
  };
  const accel::Scene& scene = session_.scene();
  // The corner under the press (within 8 pixels), which a drag from there moves.
  int grabbed = -1;
  if (click_.held()) {
    const glm::vec2 press = plane(r.press_pos);
    float best = 8.0f * camera_.units_per_pixel(static_cast<float>(view_.w));
    for (size_t v = 0; v < scene.vertex_count(); ++v) {
      const float d = glm::length(glm::vec2(scene.positions()[v]) - press);
      if (d <= best) best = d, grabbed = static_cast<int>(v);
    }
  }
  const BlackboardAction a = board_.update(r, plane(r.press_pos), plane(r.pos), click_.dragging(), grabbed);
  const std::string& spec = session_.scene_info().spec;
  switch (a.kind) {
    case BlackboardAction::Kind::AddTriangle: (void)add_triangle_2d(a.triangle); break;
    case BlackboardAction::Kind::ShootRay: set_ray(a.ray, "dragged 2D ray"); break;
    case BlackboardAction::Kind::MoveVertex:
      if (static_cast<size_t>(a.vertex) < scene.vertex_count() &&
          glm::vec2(scene.positions()[static_cast<size_t>(a.vertex)]) != a.position) {
        session_.set_scene(accel::scene2d_with_vertex_moved(scene, static_cast<uint32_t>(a.vertex), a.position.x,
                                                            a.position.y),
                           spec, true);
        sync_session();
      }
      break;
    case BlackboardAction::Kind::None: break;
  }
  if (!right.click) return;
  // A right click deletes the triangle under it (the last drawn, on top, when several are):
  // the one a 2D ray of length 0 from that point hits (docs/hits.md: the closed triangle).
  accel::Ray at;
  at.org = accel::Vec3(plane(right.press_pos), 0.0f);
  at.dir = accel::Vec3(1.0f, 0.0f, 0.0f);
  at.tmax = 0.0f;
  const accel::PlanarRayTester under(at);
  for (size_t k = scene.triangle_count(); k-- > 0;) {
    double t, u, v;
    if (!scene.degenerate(uint32_t(k)) &&
        under.intersect(scene.vertex(uint32_t(k), 0), scene.vertex(uint32_t(k), 1), scene.vertex(uint32_t(k), 2), 0.0,
                        &t, &u, &v)) {
      session_.set_scene(accel::scene2d_without_triangle(scene, uint32_t(k)), spec, true);
      sync_session();
      return;
    }
  }
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
