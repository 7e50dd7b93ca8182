#pragma once
// App: everything the viewer remembers between frames (scene, structure, debug ray, camera,
// GL resources, UI state). main.cpp owns the window and ImGui's backends and calls, per
// frame, update() between ImGui::NewFrame() and ImGui::Render(), then draw(). Scripts
// (--script) go through execute().
//
// The member functions are spread over four files:
//   app.cpp         lifecycle, scene and structure (background builds), input, drawing
//   app_ray.cpp     the debug ray: shooting, replay, highlights of the current step, compare, sweep
//   app_ui.cpp      the panels, one function each, and the lecture (large-font) mode
//   app_script.cpp  the script commands
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bench_chart.h"
#include "camera.h"
#include "heatmap.h"
#include "panels.h"
#include "presets.h"
#include "renderer.h"
#include "result.h"
#include "scene.h"
#include "script.h"
#include "workbench.h"

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

/// What the script runner needs from main(): rendering and the window.
class ScriptHost {
 public:
  virtual ~ScriptHost() = default;
  /// Resizes the window (and waits until the framebuffer has the new size).
  virtual std::optional<accel::Error> resize(int width, int height) = 0;
  /// Renders `frames` complete frames (update, draw, ImGui).
  virtual void render(int frames) = 0;
  /// Renders and writes the finished frame to `path` (PNG).
  virtual std::optional<accel::Error> screenshot(const std::string& path) = 0;
  /// Renders `frames` frames, waiting for the GPU after each; returns the mean milliseconds.
  virtual double measure_frames(int frames) = 0;
  /// Framebuffer size in pixels.
  virtual glm::ivec2 framebuffer_size() const = 0;
  /// The OpenGL renderer (GL_RENDERER), e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  virtual std::string gl_renderer() const = 0;
};

/// The viewer's state and per-frame logic.
class App {
 public:
  App();
  ~App();
  App(const App&) = delete;
  App& operator=(const App&) = delete;

  /// Loads `spec` ("procedural:NAME" or an OBJ path) with accel::load_scene, makes it the
  /// current scene, frames the camera on it and rebuilds the structure over it. On failure
  /// the previous scene stays and the error (one line) is returned and shown in the panel.
  /// Needs no GL: main() loads the command-line scene before a window exists.
  std::optional<accel::Error> load_scene(const std::string& spec);

  /// Creates the GL resources from the shaders in `shader_dir` and installs the window's
  /// callbacks. Needs `window`'s GL 3.3 context current with glad loaded.
  std::optional<accel::Error> init(GLFWwindow* window, const std::string& shader_dir, const Fonts& fonts);

  /// Queues a scene to load at the start of the next update() (used by the drop callback,
  /// which runs inside glfwPollEvents, outside any ImGui frame).
  void request_load(std::string spec);

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
  void set_synchronous(bool synchronous) { synchronous_ = synchronous; }

  /// Runs one script command; rendering commands go through `host`. Errors are the
  /// message only (the caller adds "SCRIPT:LINE: ").
  std::optional<accel::Error> execute(const ScriptCommand& command, ScriptHost& host);

  /// The scene currently shown.
  const accel::Scene& scene() const { return *scene_; }

  /// Loads a bench JSON file (accelviz-cli bench --out-json) into the "Speed vs error"
  /// chart and opens it. On failure the previous chart stays and the one-line error
  /// ("PATH: ...") is returned and shown in the chart's file row. Needs no GL.
  std::optional<accel::Error> load_bench(const std::string& path) { return load_bench_into(chart_, path); }

 private:
  // ---- app.cpp: structure and scene
  void request_structure(const StructureRequest& request);
  void start_build(const StructureRequest& request);
  void poll_build();
  void install_structure(BuiltPtr built);
  StructureRequest request_from_editor() const;
  void set_editor(const StructureRequest& request);
  /// Shows structure `name` with `params` (others at their defaults, the editor's kernel
  /// kept): fills the editor and requests the build.
  void switch_structure(const std::string& name, const std::vector<std::string>& params);
  bool structure_matches_scene() const { return built_ && built_->scene == scene_; }
  void frame_scene() { frame_requested_ = true; }
  void update_camera_input();
  void update_shortcuts();
  void update_window_title();
  void upload_geometry();
  void refresh_geometry();
  void apply_preset(const Preset& preset);
  void draw_structure(const FrameView& view);

  // ---- app_ray.cpp: debug ray
  void shoot_ray_at_pixel(float px, float py, bool from_saved_view = false);
  void set_ray(const accel::Ray& ray, const std::string& origin);
  void replay_ray();
  void rebuild_highlights();
  void start_compare();
  void poll_compare();
  void start_sweep();
  void poll_heatmap(float dt);
  void request_heatmap_now();
  std::string hit_line() const;
  std::string step_line() const;

  // ---- app_ui.cpp: panels
  void apply_lecture_mode();
  void layout_windows();
  void main_panel();
  void scene_section();
  void structure_section();
  void parameter_widgets();
  void display_section();
  void heatmap_section();
  void sweep_section();
  void ray_panel();
  void steps_panel();
  void code_panel();
  void compare_panel();
  void sweep_panel();
  void legend_panel();
  void status_overlay();

  // ---- Scene and what the panel shows about it
  std::shared_ptr<const accel::Scene> scene_;
  SceneInfo scene_info_;
  bool scene_uploaded_ = false;  // false after a load until draw() uploads it
  std::vector<std::string> pending_loads_;
  std::vector<Preset> presets_;
  int preset_index_ = 0;

  // ---- Structure: the one drawn (built_), the builds in flight, the editor's values
  BuiltPtr built_;
  StructureGeometry geometry_;                      // built_'s nodes as instances
  Job<accel::Result<BuiltPtr>> build_job_;
  std::optional<StructureRequest> queued_request_;  // asked for while a build was running
  StructureRequest requested_;                      // the latest request (shown as "building")
  std::string build_error_;
  bool geometry_dirty_ = false;                     // built_ changed: re-upload instances
  int editor_structure_ = 0;                        // index into structure_registry()
  std::vector<std::string> editor_values_;          // per parameter of that structure
  std::vector<bool> editor_explicit_;               // set by the user (else the default)
  accel::Kernel editor_kernel_ = accel::Kernel::Watertight;
  bool synchronous_ = false;

  // ---- Display
  Camera camera_;
  bool frame_requested_ = true;
  MeshStyle mesh_style_;
  LineStyle bounds_style_;
  glm::vec4 background_{0.075f, 0.085f, 0.105f, 1.0f};
  enum class DepthFilter { All, Leaves, One, Range };
  DepthFilter depth_filter_ = DepthFilter::All;
  int depth_one_ = 0, depth_lo_ = 0, depth_hi_ = 64;
  bool show_nodes_ = true;
  bool show_planes_ = true;
  bool hide_empty_leaves_ = true;
  bool empty_cells_ = false;
  int coloring_ = 0;  // 0 auto (count for grids, depth otherwise), 1 depth, 2 count
  float node_alpha_ = 0.55f;
  bool xray_ = true;  // nodes behind the mesh drawn faintly
  NodeFilter uploaded_filter_;     // the filter of the instances on the GPU
  size_t drawn_nodes_ = 0;         // instances on the GPU (boxes + spheres)
  bool depth_auto_limited_ = false;  // a huge structure opened with fewer levels shown
  NodeFilter current_filter() const;

  // ---- Debug ray and its animation
  DebugRay ray_;
  bool highlights_dirty_ = true;
  bool highlights_upload_ = false;  // rebuilt on the CPU, not yet on the GPU
  size_t highlight_step_ = ~size_t(0);
  accel::TraceHighlight highlight_;
  int code_line_ = -1;
  bool follow_step_ = true;             // scroll the step list to the current step
  size_t steps_scrolled_ = ~size_t(0);  // step the list was last scrolled to
  int code_scrolled_ = -2;              // code line last scrolled into view
  bool shoot_from_saved_ = false;       // clicks shoot from the saved viewpoint
  std::optional<accel::PinholeCamera> saved_view_;
  float typed_ray_[6] = {0, 0, 5, 0, 0, -1};
  bool show_trail_ = true, show_culled_ = true, show_pending_ = true;
  std::vector<Segment> highlight_segments_;
  std::vector<ColorVertex> highlight_triangles_;
  std::vector<ColorVertex> highlight_lines_;  // thin: culled and pending nodes

  // ---- Compare and sweep
  Job<std::vector<CompareRow>> compare_job_;
  std::shared_ptr<std::atomic<int>> compare_progress_;
  std::vector<CompareRow> compare_rows_;
  accel::Ray compare_ray_;
  bool compare_stale_ = false;
  Job<accel::Status> sweep_job_;
  std::shared_ptr<SweepProgress> sweep_progress_;
  SweepRequest sweep_request_;
  std::string sweep_error_;
  int sweep_param_ = 0;
  float sweep_lo_ = 0.5f, sweep_hi_ = 4.0f;
  int sweep_steps_ = 10;
  bool sweep_log_ = false;

  // ---- Heat map
  bool heatmap_on_ = false;
  accel::CostMetric heatmap_metric_ = accel::CostMetric::NodesVisited;
  int heatmap_divisor_ = 4;  // image resolution = framebuffer / divisor
  float heatmap_alpha_ = 0.78f;
  /// What a cost image depends on: it is recomputed when any of this changes.
  struct HeatmapInputs {
    accel::PinholeCamera camera;
    const BuiltStructure* built = nullptr;
    accel::CostMetric metric = accel::CostMetric::NodesVisited;
    glm::ivec2 size{0, 0};
    bool operator==(const HeatmapInputs& o) const {
      return camera.eye == o.camera.eye && camera.target == o.camera.target && camera.fovy_deg == o.camera.fovy_deg &&
             built == o.built && metric == o.metric && size == o.size;
    }
  };
  HeatmapInputs heatmap_inputs() const;
  Job<accel::CostImage> heatmap_job_;
  HeatmapInputs heatmap_running_;  // inputs of the job in flight
  HeatmapInputs heatmap_shown_;    // inputs of heatmap_image_
  HeatmapInputs heatmap_last_;     // inputs seen last frame (for the debounce)
  accel::CostImage heatmap_image_;
  bool heatmap_has_image_ = false;
  bool heatmap_uploaded_ = true;
  double heatmap_still_ = 0.0;     // seconds the inputs have been unchanged
  glm::ivec2 framebuffer_{1280, 720};
  /// The 3D view: the part of the framebuffer between the panels docked left and right
  /// (x, y from the top-left, width, height; framebuffer pixels), so nothing hides the
  /// framed scene. The camera's aspect, picking and the heat map all use it.
  glm::ivec4 view_{0, 0, 1280, 720};
  float dock_left_ = 0.0f, dock_right_ = 0.0f;  // window coordinates, this frame's panels
  glm::ivec2 view_size() const { return {view_.z, view_.w}; }
  void note_docked_window();
  void update_view_rect();

  // ---- UI
  struct WindowRect {
    glm::vec2 pos{0.0f}, size{0.0f};
  };
  struct Layout {
    WindowRect main, ray, code, steps, bottom, legend, status, chart;
    bool apply = false;  // this frame: move the windows to these rectangles
  } layout_;
  int layout_frames_ = 2;      // frames left that (re)apply the layout
  ScenePanelState panel_;
  struct Panels {
    bool main = true, ray = true, steps = true, code = true, compare = false, sweep = false, legend = true;
  } panels_;
  BenchChartState chart_;      // the "Speed vs error" window (bench_chart_panel.cpp)
  bool ui_visible_ = true;
  bool lecture_mode_ = false;  // large fonts, high contrast
  bool lecture_mode_applied_ = false;
  glm::vec2 layout_size_{0.0f};
  FrameTiming timing_;
  Fonts fonts_;
  float time_ = 0.0f;
  bool mouse_pressed_in_view_ = false;
  glm::vec2 mouse_press_pos_{0.0f};
  float mouse_drag_ = 0.0f;

  // ---- Window and GL resources: empty before init() and after shutdown()
  using KeyCallback = void (*)(GLFWwindow*, int key, int scancode, int action, int mods);
  GLFWwindow* window_ = nullptr;
  KeyCallback previous_key_callback_ = nullptr;  // ImGui's, which ours chains to
  struct KeyPress {
    int key;
    int mods;
  };
  std::vector<KeyPress> pressed_keys_;  // GLFW keys pressed (or repeated) since the last update()
  std::optional<Renderer> renderer_;
  std::optional<ColorBatch> bounds_lines_;
  std::optional<InstancedNodes> box_nodes_;
  std::optional<InstancedNodes> sphere_nodes_;
  std::optional<InstancedNodes> plane_nodes_;
  std::optional<SegmentBatch> segments_;
  std::optional<ColorBatch> highlight_tris_gl_;
  std::optional<ColorBatch> highlight_lines_gl_;
  std::optional<HeatmapTexture> heatmap_texture_;
};

}  // namespace viz
