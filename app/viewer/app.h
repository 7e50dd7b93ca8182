#pragma once
// App: everything the viewer remembers between frames (scene, camera, GL resources, UI
// state). main.cpp owns the window and ImGui's backends and calls, per frame,
// update() between ImGui::NewFrame() and ImGui::Render(), then draw().
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "camera.h"
#include "panels.h"
#include "renderer.h"
#include "result.h"
#include "scene.h"

struct GLFWwindow;

namespace viz {

/// The viewer's state and per-frame logic.
class App {
 public:
  /// Loads `spec` ("procedural:NAME" or an OBJ path) with accel::load_scene, makes it the
  /// current scene and frames the camera on it. On failure the previous scene stays and
  /// the error (one line) is returned and shown in the panel. Needs no GL: main() loads
  /// the command-line scene before a window exists.
  std::optional<accel::Error> load_scene(const std::string& spec);

  /// Creates the GL resources from the shaders in `shader_dir` and installs the window's
  /// file-drop callback. Needs `window`'s GL 3.3 context current with glad loaded.
  std::optional<accel::Error> init(GLFWwindow* window, const std::string& shader_dir);

  /// Queues a scene to load at the start of the next update() (used by the drop callback,
  /// which runs inside glfwPollEvents, outside any ImGui frame).
  void request_load(std::string spec);

  /// Camera input, queued loads and the panels of one frame; `dt` is the seconds since the
  /// previous frame. Call between ImGui::NewFrame() and ImGui::Render().
  void update(float dt);

  /// Draws the scene into the default framebuffer of the given size (pixels). Call before
  /// rendering ImGui's draw data, which goes on top.
  void draw(int framebuffer_width, int framebuffer_height);

  /// Releases the GL resources while the context is still current. Idempotent.
  void shutdown();

  /// Shows or hides the panels (H toggles them too); hidden gives clean screenshots.
  void set_ui_visible(bool visible) { ui_visible_ = visible; }

  /// The scene currently shown.
  const accel::Scene& scene() const { return scene_; }

 private:
  /// Asks draw() to frame the scene: only it knows the viewport's aspect ratio.
  void frame_scene() { frame_requested_ = true; }
  void update_camera_input();
  void update_shortcuts();
  void update_window_title();

  // Scene and what the panel shows about it.
  accel::Scene scene_;
  SceneInfo scene_info_;
  bool scene_uploaded_ = false;  // false after a load until draw() uploads it
  std::vector<std::string> pending_loads_;

  // View.
  Camera camera_;
  bool frame_requested_ = true;
  MeshStyle mesh_style_;
  LineStyle bounds_style_;
  glm::vec4 background_{0.075f, 0.085f, 0.105f, 1.0f};

  // UI.
  ScenePanelState panel_;
  bool ui_visible_ = true;
  FrameTiming timing_;

  // Window and GL resources: empty before init() and after shutdown().
  using KeyCallback = void (*)(GLFWwindow*, int key, int scancode, int action, int mods);
  GLFWwindow* window_ = nullptr;
  KeyCallback previous_key_callback_ = nullptr;  // ImGui's, which ours chains to
  std::vector<int> pressed_keys_;  // GLFW key codes pressed since the last update()
  std::optional<Renderer> renderer_;
  std::optional<ColorBatch> bounds_lines_;
};

}  // namespace viz
