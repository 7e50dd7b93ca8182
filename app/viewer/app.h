#pragma once
// App: the viewer's lifecycle, window layout, input dispatch and script dispatch. The
// tools (app/viewer/tools/) own their state, panels and drawing, and declare their keys as
// rows and their script verbs as registrations (commands.h); App keeps the global ones,
// gathers the rest and dispatches, and passes each tool the little it needs from the
// others (ToolHost: the current structure, the camera, the view rectangle). main.cpp owns
// the window and ImGui's backends and calls, per frame, update() between ImGui::NewFrame()
// and ImGui::Render(), then draw(). Scripts (--script) go through execute().
//
//   app.cpp         lifecycle, the rows, per-frame update, input and the global keys, drawing,
//                   session events
//   app_ui.cpp      the window layout, the main panel (its help made from the key rows), the
//                   panels shown, the lecture mode
//   app_script.cpp  script dispatch (by the verb's name; the global verbs: global_verbs.h)
//   app_blackboard.cpp  the 2D mode (issue #32): a 2D scene seen from above, edited with the
//                   mouse, and its verbs
//   app_state.cpp   the state as a script (save-state, --restore)
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bench_chart.h"
#include "camera.h"
#include "commands.h"
#include "input.h"
#include "panels.h"
#include "renderer.h"
#include "result.h"
#include "script.h"
#include "tool_host.h"
#include "tools/blackboard_editor.h"
#include "tools/build_player.h"
#include "tools/compare_tool.h"
#include "tools/heatmap_tool.h"
#include "tools/node_display.h"
#include "tools/playlist_tool.h"
#include "tools/ray_debugger.h"
#include "tools/recorder.h"
#include "tools/structure_session.h"
#include "tools/sweep_tool.h"
#include "tools/trap_tool.h"
#include "tools/vars_panel.h"
#include "tools/tree_diagram.h"
#include "view_layout.h"

struct GLFWwindow;
struct ImFont;

namespace viz {

/// Fonts main() loaded: the normal and the lecture (large) size, proportional and mono.
struct Fonts {
  ImFont* ui = nullptr;
  ImFont* ui_large = nullptr;
  ImFont* mono = nullptr;
  ImFont* mono_large = nullptr;
};

/// The viewer: its tools, the camera, the window layout.
class App : private ToolHost {
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

  /// Queues a scene to load at the start of the next update() (used by the drop callback,
  /// which runs inside glfwPollEvents, outside any ImGui frame).
  void request_load(std::string spec) { session_.request_load(std::move(spec)); }

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
  void set_ui_visible(bool visible) { ui_visible_ = visible; }

  /// Script mode: builds, heat maps, comparisons and sweeps run synchronously, and the
  /// animation does not advance on its own.
  void set_synchronous(bool synchronous);
  /// The builds' memory budget in bytes (0: the default); rebuilds the current structure.
  void set_memory_limit(size_t bytes) { session_.set_memory_limit(bytes); }

  /// Runs one script command through its verb's run; rendering commands go through `host`.
  /// Errors are the message only (the caller adds "SCRIPT:LINE: ").
  accel::Status execute(const ScriptCommand& command, ScriptHost& host);
  /// The key rows, App's global ones first, in the order a press is offered to them: what
  /// the help and `accelviz --list keys` show. Needs no GL.
  const std::vector<KeyGroup>& key_groups() const { return key_groups_; }

  /// The scene currently shown.
  const accel::Scene& scene() const { return session_.scene(); }

  /// Loads a lecture playlist (playlist.h) and queues its first state, which runs once the
  /// window is up (execute() in a script runs it at once). Errors "FILE:LINE: ...". Needs no GL.
  accel::Status load_playlist(const std::string& path) override;

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
  void capture(bool with_ui) { recorder_.capture(with_ui, view_, framebuffer_); }
  /// Whether capture(with_ui) has anything to do this frame.
  bool wants_capture(bool with_ui) const { return recorder_.wants_capture(with_ui); }

  /// Loads a bench JSON file (accelviz-cli bench --out-json) into the "Speed vs error"
  /// chart and opens it. On failure the previous chart stays and the one-line error
  /// ("PATH: ...") is returned and shown in the chart's file row. Needs no GL.
  accel::Status load_bench(const std::string& path) { return load_bench_into(chart_, path); }

 private:
  // ---- ToolHost: what the tools' rows ask of App
  StructureSession& session() override { return session_; }
  RayDebugger& ray() override { return ray_; }
  BuildPlayer& build() override { return build_; }
  bool synchronous() const override { return synchronous_; }
  accel::Status loaded() const override { return synchronous_ ? session_.need_structure() : accel::Status{}; }
  void sync_session() override;
  void relayout() override { layout_frames_ = 2; }
  void show_ui() override { ui_visible_ = true; }
  void settle_camera(ScriptHost& host) override;
  glm::ivec4 view_area() const override { return view_; }
  glm::ivec2 framebuffer() const override { return framebuffer_; }
  void walk_recorded(accel::PlaybackClock& clock, size_t from, ScriptHost& host) override;
  void set_ray(const accel::Ray& ray, const std::string& origin) override;
  void shoot_at_pixel(float px, float py, bool from_saved_view) override;
  void start_compare() override;
  accel::Status start_sweep() override;
  void construct() override { build_.construct(session_.scene_ptr(), session_.current_request(), synchronous_); }
  HeatmapView heatmap_view() const override;
  accel::Status apply_preset(const Preset& preset) override;
  accel::Status load_trap(const std::string& name) override;
  // The playlist: go to a state (queued; the viewer reset first when going back), run the
  // queued commands (`host` null: one per frame in the window, only when no build runs).
  void go_to_state(size_t index) override;
  void run_playlist(ScriptHost* host) override;

  // ---- app.cpp
  /// App's own keys: frame, 2D, hide the panels, lecture mode, record, screenshot, Esc.
  KeyGroup global_keys();
  void reset_for_playlist();
  accel::Status toggle_recording();
  void switch_structure(const StructureChoice& choice) { session_.switch_structure(choice.name, choice.params); }
  void frame_scene() { frame_requested_ = true; }
  void update_camera_input();
  void update_shortcuts();
  void update_window_title();
  glm::ivec2 view_size() const { return {view_.z, view_.w}; }

  // ---- The verbs whose runs set App's own state: global_verbs.h (size, camera, panel,
  // large, colors, screenshot, save-state, print-frame-time) and tools/blackboard_verbs.h
  // (the 2D mode)
  template <class Verbs>
  friend void global_verbs(Verbs& verbs);
  template <class Verbs>
  friend void blackboard_verbs(Verbs& verbs);

  // ---- app_blackboard.cpp: the 2D mode
  /// 2D: the blackboard (the current 2D scene, else an empty one); 3D: back to the last 3D scene.
  accel::Status set_mode_2d(bool on);
  bool mode_2d() const { return session_.scene().planar(); }
  /// Loads a 2D scene file (scene2d.h) onto the blackboard.
  accel::Status load_scene2d(const std::string& path);
  /// Adds a triangle (x1 y1 x2 y2 x3 y3) to the blackboard's scene and rebuilds.
  accel::Status add_triangle_2d(const std::array<float, 6>& xy);
  /// The debug ray in the plane.
  accel::Status set_ray_2d(float ox, float oy, float dx, float dy);
  /// Writes the blackboard's scene to `path` as a 2D scene file (never half written).
  accel::Status save_scene2d(const std::string& path);
  /// The Scene section's blackboard lines: the 2D switch, and in 2D the file to save to.
  void board_section();
  /// The mouse on the blackboard: the left button's clicks place corners, its drags move a
  /// corner or shoot the ray; a right click deletes the triangle under the cursor.
  void update_board_input(const ClickResult& left, const ClickResult& right);
  /// 2D: the grid of world units (`grid`, drawn first), or the corners placed and the ray
  /// being dragged (drawn over the structure).
  void draw_board(bool grid);
  /// What the camera frames: the scene's box, or a 10 x 10 board for an empty 2D scene.
  accel::Aabb frame_box() const;

  // ---- app_ui.cpp
  void apply_lecture_mode();
  /// `panel NAME on|off`: one panel ("all": every one) shown or hidden.
  void set_panel(const std::string& name, bool on);
  void layout_windows();
  PanelPlace place(const WindowRect& rect, bool docks = true);
  void main_panel();
  void traversal_numbers();
  void status_overlay();

  // ---- The tools
  StructureSession session_;
  NodeDisplay nodes_;
  RayDebugger ray_;
  BuildPlayer build_;  // the construction mode
  CompareTool compare_;
  SweepTool sweep_;
  HeatmapTool heatmap_;
  VarsPanel vars_;  // the traversal's variables and the t-axis strip
  TrapTool trap_;   // the lecture's traps: the naive answer beside the right one
  TreeDiagram tree_;  // the "Tree" window (T)
  PlaylistTool playlist_;  // the lecture playlist (PgDn / PgUp)
  Recorder recorder_;      // GIF / MP4 of the animation (R), screenshots (F12)
  struct StepSeen {
    size_t trace = ~size_t(0), build = ~size_t(0);
    bool build_mode = false;
    bool operator==(const StepSeen&) const = default;
  } step_seen_;  // the animation's step at the last frame: a new one is recorded
  BenchChartState chart_;  // the "Speed vs error" window (bench_chart_panel.cpp)
  BlackboardEditor board_;  // the 2D mode's mouse editing
  std::string last_3d_scene_ = "procedural:cornell";  // what `mode 3d` goes back to
  std::string board_path_ = "blackboard.scene2d";     // the Scene section's save field
  std::string board_status_;                          // what the last save said

  // ---- The rows: keys in the order a press is offered, every verb with its run
  std::vector<KeyGroup> key_groups_;
  VerbTable verbs_;

  // ---- Camera, input and the 3D view
  Camera camera_;
  bool frame_requested_ = true;
  bool synchronous_ = false;
  ClickTracker click_;
  ClickTracker right_click_;  // 2D: a right click deletes a triangle (a right drag pans)
  /// The 3D view: the part of the framebuffer between the panels docked left and right
  /// (x, y from the top-left, width, height; framebuffer pixels), so nothing hides the
  /// framed scene. The camera's aspect, picking and the heat map all use it.
  glm::ivec4 view_{0, 0, 1280, 720};
  glm::ivec2 framebuffer_{1280, 720};
  DockEdges dock_;  // this frame's docked panels
  glm::vec4 background_{0.075f, 0.085f, 0.105f, 1.0f};

  // ---- Window layout and UI
  PanelLayout layout_;
  bool layout_apply_ = false;  // this frame: move the windows to layout_
  int layout_frames_ = 2;      // frames left that (re)apply the layout
  glm::vec2 layout_size_{0.0f};
  struct Panels {
    bool main = true, ray = true, steps = true, code = true, legend = true;
  } panels_;
  bool ui_visible_ = true;
  bool lecture_mode_ = false;  // large fonts, high contrast
  bool lecture_mode_applied_ = false;
  bool vars_column_ = true;  // the Variables panel is in the left column (main_panel() is shorter)
  FrameTiming timing_;
  Fonts fonts_;

  // ---- Window and GL: empty before init() and after shutdown()
  using KeyCallback = void (*)(GLFWwindow*, int key, int scancode, int action, int mods);
  GLFWwindow* window_ = nullptr;
  std::string window_title_;  // as last set
  KeyCallback previous_key_callback_ = nullptr;  // ImGui's, which ours chains to
  std::vector<KeyPress> pressed_keys_;  // GLFW keys pressed (or repeated) since the last update()
  std::optional<Renderer> renderer_;
  std::optional<ColorBatch> board_lines_;  // the 2D mode's grid, corners and dragged ray
};

}  // namespace viz
