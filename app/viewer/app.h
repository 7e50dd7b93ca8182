#pragma once
// App: the viewer's lifecycle, its list of tools, the window and its layout, the camera,
// and the dispatch of keys and script commands. The tools (app/viewer/tools/, one interface:
// tools/tool.h) own their state, keys, verbs, panels and drawing; App calls each in the
// list's order (tools/tool_list.cpp) and names none. main.cpp owns the window and ImGui's
// backends and calls, per frame, update() between ImGui::NewFrame() and ImGui::Render(),
// then draw(). Scripts (--script) go through execute().
//
//   app.cpp         lifecycle, the per-frame loop over the tools, the keys, drawing
//   app_ui.cpp      the main panel (the tools' sections; the keys' help made from their rows)
//   app_script.cpp  script dispatch (by the verb's name; App's own verbs: global_verbs.h)
//   app_state.cpp   the state as a script (save-state, --restore)
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera_control.h"
#include "commands.h"
#include "panels.h"
#include "renderer.h"
#include "result.h"
#include "script.h"
#include "tool_host.h"
#include "window_layout.h"

struct GLFWwindow;

namespace viz {

/// The viewer: its tools, the camera, the window layout.
class App final : private ToolHost {
 public:
  App();
  ~App();
  App(const App&) = delete;
  App& operator=(const App&) = delete;

  /// Loads `spec` ("procedural:NAME" or an OBJ path) with accel::load_scene, makes it the
  /// current scene, frames the camera on it and rebuilds the structure over it. On failure
  /// the previous scene stays and the error (one line) is returned and shown in the panel.
  /// Needs no GL: main() loads the command-line scene before a window exists.
  accel::Status load_scene(const std::string& spec);

  /// Creates the GL resources from the shaders in `shader_dir` and installs the window's
  /// callbacks. Needs `window`'s GL 3.3 context current with glad loaded.
  accel::Status init(GLFWwindow* window, const std::string& shader_dir, const Fonts& fonts);

  /// Camera input, finished background jobs, the animation and the panels of one frame;
  /// `dt` is the seconds since the previous frame. Call between ImGui::NewFrame() and
  /// ImGui::Render().
  void update(float dt);

  /// Draws the scene into the default framebuffer of the given size (pixels). Call before
  /// rendering ImGui's draw data, which goes on top.
  void draw(int framebuffer_width, int framebuffer_height);

  /// Releases the GL resources while the context is still current and waits for the
  /// background jobs. Idempotent.
  void shutdown();

  /// Shows or hides the panels (H toggles them too); hidden gives clean screenshots.
  void set_ui_visible(bool visible) { layout_.set_ui_visible(visible); }

  /// Script mode: builds, heat maps, comparisons and sweeps run synchronously, and the
  /// animation does not advance on its own.
  void set_synchronous(bool synchronous);
  /// The builds' memory budget in bytes (0: the default); rebuilds the current structure.
  void set_memory_limit(size_t bytes);

  /// Runs one script command through its verb's run; rendering commands go through `host`.
  /// Errors are the message only (the caller adds "SCRIPT:LINE: ").
  accel::Status execute(const ScriptCommand& command, ScriptHost& host) override;
  /// The key rows, App's global ones first, in the order a press is offered to them: what
  /// the help and `accelviz --list keys` show. Needs no GL.
  const std::vector<KeyGroup>& key_groups() const { return key_groups_; }

  /// Loads a lecture playlist (playlist.h) and queues its first state, which runs once the
  /// window is up (execute() in a script runs it at once). Errors "FILE:LINE: ...". Needs no GL.
  accel::Status load_playlist(const std::string& path) { return ToolHost::load_playlist(path); }

  /// Switches to structure `name` with its key=value `params` (the command line's
  /// --structure and --param; checked as a script's `structure` line is). Needs no GL.
  accel::Status set_structure(const std::string& name, const std::vector<std::string>& params);
  /// Moves the loaded playlist to its state `number`, counted from 1 (the command line's
  /// --state). Error when no playlist is loaded or it has no such state.
  accel::Status go_to_state_number(size_t number);

  /// The state as script commands (scene, structure, kernel, camera, ray, step): what
  /// --restore reopens (app_state.cpp).
  std::string state_script() const;
  /// Writes state_script() to `path` (its folder made; never half written).
  accel::Status save_state(const std::string& path) const;

  /// Recording and screenshots read the frame back: main() calls this after the 3D view is
  /// drawn (with_ui = false) and again after the panels (true), before the buffer swap.
  void capture(bool with_ui);
  /// Whether capture(with_ui) has anything to do this frame.
  bool wants_capture(bool with_ui) const;

  /// Loads a bench JSON file (accelviz-cli bench --out-json) into the "Speed vs error"
  /// chart and opens it. On failure the previous chart stays and the one-line error
  /// ("PATH: ...") is returned and shown in the chart's file row. Needs no GL.
  accel::Status load_bench(const std::string& path);

 private:
  // ---- ToolHost
  std::span<Tool* const> tools() const override { return tool_list_; }
  bool synchronous() const override { return synchronous_; }
  WindowLayout& layout() const override { return layout_; }
  CameraControl& camera() const override { return camera_; }
  void notify(ToolEvent event) override;
  void resize_window(int width, int height) override;
  void refresh_title() override;

  // ---- app.cpp
  /// App's own keys: frame the scene, hide the panels, lecture mode.
  KeyGroup global_keys();
  void update_shortcuts();
  void update_timing(float dt);

  // ---- The verbs whose runs set App's own state: global_verbs.h (size, camera, panel,
  // large, colors, screenshot, save-state, print-frame-time)
  template <class Verbs>
  friend void global_verbs(Verbs& verbs);
  /// `panel NAME on|off`: one panel ("all": every one) shown or hidden.
  void set_panel(const std::string& name, bool on);

  // ---- app_ui.cpp
  void main_panel();
  void colors_widget();

  // ---- The tools, in the order App calls them (tools/tool_list.cpp)
  std::vector<std::unique_ptr<Tool>> tools_;
  std::vector<Tool*> tool_list_;

  // ---- The rows: keys in the order a press is offered, every verb with its run
  std::vector<KeyGroup> key_groups_;
  VerbTable verbs_;

  // ---- The 3D view, the window's layout, the frame
  mutable CameraControl camera_;   // the tools move it through ToolHost
  mutable WindowLayout layout_;
  bool synchronous_ = false;
  FrameTiming timing_;

  // ---- Window and GL: empty before init() and after shutdown()
  using KeyCallback = void (*)(GLFWwindow*, int key, int scancode, int action, int mods);
  GLFWwindow* window_ = nullptr;
  std::string window_title_;  // as last set
  KeyCallback previous_key_callback_ = nullptr;  // ImGui's, which ours chains to
  std::vector<KeyPress> pressed_keys_;  // GLFW keys pressed (or repeated) since the last update()
  std::optional<Renderer> renderer_;
};

}  // namespace viz
