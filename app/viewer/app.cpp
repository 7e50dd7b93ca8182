#include "app.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace viz {
namespace {

// Weight of the newest frame in the smoothed frame time: about the last 20 frames count,
// so the number is readable yet follows a change within a fraction of a second.
constexpr double kTimingSmoothing = 0.05;

}  // namespace

std::optional<accel::Error> App::load_scene(const std::string& spec) {
  const auto start = std::chrono::steady_clock::now();
  accel::Result<accel::Scene> loaded = accel::load_scene(spec);
  const auto stop = std::chrono::steady_clock::now();
  if (!loaded) {
    panel_.load_error = loaded.error().message;
    return loaded.error();
  }
  scene_ = std::move(loaded.value());
  scene_info_.spec = spec;
  scene_info_.name = scene_.name();
  scene_info_.triangles = scene_.triangle_count();
  scene_info_.vertices = scene_.vertex_count();
  scene_info_.degenerate = scene_.degenerate_count();
  scene_info_.bounds = scene_.bounds();
  scene_info_.load_ms = std::chrono::duration<double, std::milli>(stop - start).count();
  scene_uploaded_ = false;
  panel_.load_error.clear();
  frame_scene();
  update_window_title();
  return std::nullopt;
}

std::optional<accel::Error> App::init(GLFWwindow* window, const std::string& shader_dir) {
  window_ = window;
  auto renderer = Renderer::create(shader_dir);
  if (!renderer) return renderer.error();
  renderer_.emplace(std::move(renderer.value()));
  bounds_lines_.emplace(GL_LINES);
  scene_uploaded_ = false;

  // A subtle box around the scene: shows its extent without competing with the mesh;
  // edges hidden by the mesh still show, fainter.
  bounds_style_.tint = glm::vec4(1.0f);
  bounds_style_.hidden_tint = glm::vec4(1.0f, 1.0f, 1.0f, 0.35f);

  panel_.presets = accel::procedural_scene_names();
  const std::string prefix = "procedural:";
  if (scene_info_.spec.starts_with(prefix)) {
    const auto it = std::find(panel_.presets.begin(), panel_.presets.end(),
                              scene_info_.spec.substr(prefix.size()));
    if (it != panel_.presets.end()) panel_.preset = static_cast<int>(it - panel_.presets.begin());
  }

  // GLFW callbacks are plain functions: the window's user pointer leads back to us.
  // ImGui's GLFW backend does not use the user pointer, and installs no drop callback.
  glfwSetWindowUserPointer(window, this);
  glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
    // Several files dropped at once: one scene is shown at a time, take the first.
    if (count > 0) static_cast<App*>(glfwGetWindowUserPointer(w))->request_load(paths[0]);
  });
  // Shortcuts are taken from key events rather than ImGui::IsKeyPressed(): ImGui 1.86 only
  // samples key state once per frame, so a quick tap between two slow frames (a big scene
  // on a lecture laptop) would be lost. ImGui's own callback still runs first.
  previous_key_callback_ = glfwSetKeyCallback(
      window, [](GLFWwindow* w, int key, int scancode, int action, int mods) {
        App* app = static_cast<App*>(glfwGetWindowUserPointer(w));
        if (app->previous_key_callback_ != nullptr) app->previous_key_callback_(w, key, scancode, action, mods);
        if (action == GLFW_PRESS) app->pressed_keys_.push_back(key);
      });
  update_window_title();
  return std::nullopt;
}

void App::request_load(std::string spec) { pending_loads_.push_back(std::move(spec)); }

void App::update(float dt) {
  // Loads requested since the last frame; only the last one matters to the user, but a
  // failure of an earlier one would then go unreported, so run them in order.
  std::vector<std::string> loads;
  loads.swap(pending_loads_);
  for (const std::string& spec : loads) load_scene(spec);

  update_camera_input();
  update_shortcuts();

  const double frame_ms = 1000.0 * static_cast<double>(dt);
  timing_.frame_ms = timing_.frame_ms == 0.0
                         ? frame_ms
                         : (1.0 - kTimingSmoothing) * timing_.frame_ms + kTimingSmoothing * frame_ms;
  timing_.fps = timing_.frame_ms > 0.0 ? 1000.0 / timing_.frame_ms : 0.0;

  if (!ui_visible_) return;
  const ScenePanelActions actions = scene_panel(scene_info_, timing_, panel_);
  if (actions.frame_scene) frame_scene();
  if (actions.load) load_scene(*actions.load);
}

void App::update_camera_input() {
  const ImGuiIO& io = ImGui::GetIO();
  // The mouse belongs to ImGui while it hovers a window or drags a widget; a drag that
  // started over the scene keeps going even when it crosses a panel.
  if (!io.WantCaptureMouse) {
    const float dx = io.MouseDelta.x;
    const float dy = io.MouseDelta.y;
    if (io.MouseDown[ImGuiMouseButton_Left]) {
      camera_.orbit(dx, dy);
    } else if (io.MouseDown[ImGuiMouseButton_Right] || io.MouseDown[ImGuiMouseButton_Middle]) {
      // Deltas are in window coordinates, so pan with the window's height, not the
      // framebuffer's (they differ on HiDPI screens).
      camera_.pan(dx, dy, io.DisplaySize.y);
    }
    if (io.MouseWheel != 0.0f) camera_.zoom(io.MouseWheel);
  }
}

void App::update_shortcuts() {
  std::vector<int> keys;
  keys.swap(pressed_keys_);
  // Typing "f" into the OBJ path field must not reframe the scene.
  if (ImGui::GetIO().WantCaptureKeyboard) return;
  for (const int key : keys) {
    if (key == GLFW_KEY_F) frame_scene();
    if (key == GLFW_KEY_H) ui_visible_ = !ui_visible_;
  }
}

void App::draw(int framebuffer_width, int framebuffer_height) {
  if (!renderer_ || framebuffer_width <= 0 || framebuffer_height <= 0) return;
  if (!scene_uploaded_) {
    renderer_->set_scene(scene_);
    std::vector<ColorVertex> lines;
    append_box_edges(lines, scene_.bounds(), glm::vec4(0.55f, 0.62f, 0.75f, 0.55f));
    bounds_lines_->upload(lines);
    scene_uploaded_ = true;
  }
  const float aspect = static_cast<float>(framebuffer_width) / static_cast<float>(framebuffer_height);
  if (frame_requested_) {
    camera_.frame(scene_.bounds(), aspect);
    frame_requested_ = false;
  }
  FrameView view;
  view.view = camera_.view();
  view.projection = camera_.projection(aspect);
  view.eye = camera_.eye();
  view.viewport = {framebuffer_width, framebuffer_height};
  renderer_->begin_frame(view, background_);
  renderer_->draw_mesh(mesh_style_);
  renderer_->draw_lines(*bounds_lines_, bounds_style_);
  renderer_->end_frame();
}

void App::shutdown() {
  // GL objects first: their destructors call into the context main() destroys next.
  bounds_lines_.reset();
  renderer_.reset();
  if (window_ != nullptr) {
    // Reverse order of init(): ImGui's shutdown then restores the callbacks it replaced.
    glfwSetKeyCallback(window_, previous_key_callback_);
    previous_key_callback_ = nullptr;
    glfwSetDropCallback(window_, nullptr);
    glfwSetWindowUserPointer(window_, nullptr);
    window_ = nullptr;
  }
}

void App::update_window_title() {
  if (window_ == nullptr) return;
  const std::string title =
      "accelviz - " + (scene_info_.name.empty() ? scene_info_.spec : scene_info_.name);
  glfwSetWindowTitle(window_, title.c_str());
}

}  // namespace viz
