// The blackboard (2D mode): the mode switch, editing the 2D scene (script verbs and the
// mouse), saving it, and drawing the board (blackboard_tool.h).
#include "tools/blackboard_tool.h"

#include <cmath>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "camera_control.h"
#include "planar_geometry.h"
#include "scene2d.h"
#include "tool_host.h"
#include "tools/blackboard_verbs.h"
#include "tools/structure_session.h"

namespace viz {

namespace {

bool mode_2d(const ToolHost& host) { return host.session().scene().planar(); }

}  // namespace

std::vector<KeyBinding> BlackboardTool::keys(ToolHost& host) {
  return {
      // A failed load shows in the panel.
      {GLFW_KEY_D, "D", "the blackboard (2D mode) on and off",
       [this, &host](const KeyPress&) {
         (void)set_mode_2d(!mode_2d(host), host);
         return true;
       }},
      {GLFW_KEY_ESCAPE, "Esc", "blackboard: forget the corners placed so far",
       [this](const KeyPress&) {
         editor_.clear();
         return true;
       }},
  };
}

void BlackboardTool::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<BlackboardTool> verbs(table, *this, host);
  blackboard_verbs(verbs);
}

void BlackboardTool::on_event(ToolEvent event, ToolHost& host) {
  if (event != ToolEvent::SceneLoaded) return;
  editor_.clear();
  const std::string& spec = host.session().scene_info().spec;
  if (!mode_2d(host)) last_3d_scene_ = spec;
  else if (spec.ends_with(accel::kScene2dExtension)) path_ = spec;  // saved back where it came from
}

accel::Status BlackboardTool::set_mode_2d(bool on, ToolHost& host) {
  if (on == mode_2d(host)) return {};
  StructureSession& session = host.session();
  if (!on) {
    accel::Status st = session.load_scene(last_3d_scene_);
    host.sync_session();
    return st;
  }
  // An empty board; the structure is rebuilt over it like over any scene.
  accel::Scene board;
  (void)board.mark_planar();  // no vertex: always succeeds
  session.set_scene(std::move(board), "blackboard", false);
  host.sync_session();
  return host.loaded();
}

accel::Status BlackboardTool::load_scene2d(const std::string& path, ToolHost& host) {
  auto scene = accel::load_scene2d(path);
  if (!scene) return scene.error();
  host.session().set_scene(std::move(scene.value()), path, false);
  host.sync_session();
  return host.loaded();
}

accel::Status BlackboardTool::add_triangle_2d(const std::array<float, 6>& xy, ToolHost& host) {
  if (!mode_2d(host)) return accel::make_error("add2d: not in 2D mode (mode 2d first)");
  StructureSession& session = host.session();
  session.set_scene(accel::scene2d_with_triangle(session.scene(), xy), session.scene_info().spec, true);
  host.sync_session();
  return host.loaded();
}

accel::Status BlackboardTool::set_ray_2d(float ox, float oy, float dx, float dy, ToolHost& host) {
  if (!mode_2d(host)) return accel::make_error("ray2d: not in 2D mode (mode 2d first)");
  accel::Ray r;
  r.org = {ox, oy, 0.0f};
  r.dir = {dx, dy, 0.0f};
  host.set_ray(r, "2D ray");
  return {};
}

accel::Status BlackboardTool::save_scene2d(const std::string& path, ToolHost& host) {
  if (!mode_2d(host)) return accel::make_error("save2d: not in 2D mode (mode 2d first)");
  return accel::save_scene2d(path, host.session().scene());
}

void BlackboardTool::section(ToolHost& host, PanelSection section) {
  if (section != PanelSection::Scene) return;
  bool board = mode_2d(host);
  if (ImGui::Checkbox("blackboard: 2D mode (D)", &board)) (void)set_mode_2d(board, host);  // errors show below
  if (ImGui::IsItemHovered()) {
    // What the mouse does there, from its rows (input.h): one source for the help too.
    std::string tip = "triangles in a plane seen from above; the mouse there:";
    for (const std::string& line : mouse_help_lines(true)) tip += "\n  " + line;
    ImGui::SetTooltip("%s", tip.c_str());
  }
  if (!board) return;
  ImGui::SetNextItemWidth(12.0f * ImGui::GetFontSize());
  ImGui::InputText("##board_path", &path_);
  ImGui::SameLine();
  if (ImGui::Button("Save 2D scene")) {
    const accel::Status saved = save_scene2d(path_, host);
    status_ = saved ? "saved " + path_ : saved.error().message;
  }
  if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
}

void BlackboardTool::mouse(const MouseFrame& m, ToolHost& host) {
  // The mouse on the blackboard: the left button's clicks place corners, its drags move a
  // corner or shoot the ray; a right click deletes the triangle under the cursor.
  const Camera& camera = host.camera().camera();
  if (!camera.top_down()) return;
  const ClickResult& r = m.left;
  const glm::ivec4 view = host.view_area();
  // Window coordinates -> framebuffer pixels -> the 3D view's pixels -> the plane.
  auto plane = [&](glm::vec2 window) {
    const glm::vec3 p = camera.plane_point(window.x * m.scale.x - static_cast<float>(view.x),
                                           window.y * m.scale.y - static_cast<float>(view.y), view.z, view.w);
    return glm::vec2(p.x, p.y);
  };
  StructureSession& session = host.session();
  const accel::Scene& scene = session.scene();
  // The corner under the press (within 8 pixels), which a drag from there moves.
  int grabbed = -1;
  if (m.left_held) {
    const glm::vec2 press = plane(r.press_pos);
    float best = 8.0f * camera.units_per_pixel(static_cast<float>(view.w));
    for (size_t v = 0; v < scene.vertex_count(); ++v) {
      const float d = glm::length(glm::vec2(scene.positions()[v]) - press);
      if (d <= best) best = d, grabbed = static_cast<int>(v);
    }
  }
  const BlackboardAction a = editor_.update(r, plane(r.press_pos), plane(r.pos), m.left_dragging, grabbed);
  switch (a.kind) {
    case BlackboardAction::Kind::AddTriangle: (void)add_triangle_2d(a.triangle, host); break;
    case BlackboardAction::Kind::ShootRay: host.set_ray(a.ray, "dragged 2D ray"); break;
    case BlackboardAction::Kind::MoveVertex:
      if (static_cast<size_t>(a.vertex) < scene.vertex_count() &&
          glm::vec2(scene.positions()[static_cast<size_t>(a.vertex)]) != a.position) {
        session.set_scene(accel::scene2d_with_vertex_moved(scene, static_cast<uint32_t>(a.vertex), a.position.x,
                                                           a.position.y),
                          session.scene_info().spec, true);
        host.sync_session();
      }
      break;
    case BlackboardAction::Kind::None: break;
  }
  if (m.right.click) delete_under(plane(m.right.press_pos), host);
}

void BlackboardTool::delete_under(glm::vec2 point, ToolHost& host) {
  // The last drawn triangle under `point` (on top, when several are): the one a 2D ray of
  // length 0 from that point hits (docs/hits.md: the closed triangle).
  StructureSession& session = host.session();
  const accel::Scene& scene = session.scene();
  accel::Ray at;
  at.org = accel::Vec3(point, 0.0f);
  at.dir = accel::Vec3(1.0f, 0.0f, 0.0f);
  at.tmax = 0.0f;
  const accel::PlanarRayTester under(at);
  for (size_t k = scene.triangle_count(); k-- > 0;) {
    double t, u, v;
    if (!scene.degenerate(uint32_t(k)) &&
        under.intersect(scene.vertex(uint32_t(k), 0), scene.vertex(uint32_t(k), 1), scene.vertex(uint32_t(k), 2), 0.0,
                        &t, &u, &v)) {
      session.set_scene(accel::scene2d_without_triangle(scene, uint32_t(k)), session.scene_info().spec, true);
      host.sync_session();
      return;
    }
  }
}

void BlackboardTool::draw(Renderer& renderer, ToolHost& host, DrawLayer layer) {
  if (layer == DrawLayer::Under) draw_lines(renderer, host, true);
  if (layer == DrawLayer::Over) draw_lines(renderer, host, false);
}

void BlackboardTool::draw_lines(Renderer& renderer, ToolHost& host, bool grid) {
  if (!mode_2d(host) || !lines_) return;
  const Camera& camera = host.camera().camera();
  const glm::ivec4 view = host.view_area();
  std::vector<ColorVertex> lines;
  auto line = [&](glm::vec2 a, glm::vec2 b, glm::vec4 c) {
    lines.push_back({glm::vec3(a, 0.0f), c});
    lines.push_back({glm::vec3(b, 0.0f), c});
  };
  const float upp = camera.units_per_pixel(static_cast<float>(view.w));
  if (grid) {
    // The grid of world units over the visible part of the plane, every fifth line brighter.
    const glm::vec3 lo = camera.plane_point(0.0f, static_cast<float>(view.w), view.z, view.w);
    const glm::vec3 hi = camera.plane_point(static_cast<float>(view.z), 0.0f, view.z, view.w);
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
    const std::vector<glm::vec2>& corners = editor_.pending();
    for (size_t k = 0; k < corners.size(); ++k) {
      line(corners[k] - glm::vec2(r, 0), corners[k] + glm::vec2(r, 0), yellow);
      line(corners[k] - glm::vec2(0, r), corners[k] + glm::vec2(0, r), yellow);
      if (k > 0) line(corners[k - 1], corners[k], yellow);
    }
    if (auto drag = editor_.drag_line()) line(drag->first, drag->second, yellow);
  }
  if (lines.empty()) return;
  lines_->upload(lines, GL_DYNAMIC_DRAW);
  LineStyle style;
  style.depth_test = false;
  renderer.draw_lines(*lines_, style);
}

}  // namespace viz
