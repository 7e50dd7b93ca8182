#pragma once
// The structure session: the scene (loading, what the panel shows about it, presets), the
// structure built over it (background build through a BuildRunner: a change cancels the
// running build, the newest request waits one deep), and the parameter editor. Owns the scene's GL mesh upload and its bounding-box lines.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "build_runner.h"
#include "commands.h"
#include "job.h"
#include "panels.h"
#include "presets.h"
#include "renderer.h"
#include "result.h"
#include "scene.h"
#include "tool_host.h"
#include "tools/param_editor.h"
#include "tools/tool.h"

namespace viz {

/// What happened in the session since take_events(): the App tells the other tools.
struct SessionEvents {
  bool scene_loaded = false;         ///< a new scene: old rays, comparisons and images are void
  bool structure_installed = false;  ///< a new structure is drawn (current() changed; null after a
                                     ///< failed build's replay)
  bool scene_edited = false;         ///< the blackboard's scene changed (the camera and ray stay)
};

/// What the Scene section's camera buttons asked for (the camera is App's).
struct SceneActions {
  int load_preset = -1;      ///< index into presets(): "Load preset"
  bool frame = false;        ///< "Frame scene (F)"
  bool save_view = false;    ///< "Save view"
  bool go_to_saved = false;  ///< "Go to saved"
};

/// Scene + structure + editor.
class StructureSession final : public Tool {
 public:
  // ---- The tool (tool.h)
  const char* name() const override { return "structure"; }
  void add_verbs(VerbTable& table, ToolHost& host) override;
  void init_gl() override;
  void release_gl() override;
  void wait() override;
  /// The finished build or load, and what it means for the other tools.
  void update(ToolHost& host, float dt) override;
  /// Scene: the loaded scene, presets and the camera's buttons; Structure: its choice.
  void section(ToolHost& host, PanelSection section) override;
  void sync_gl(Renderer& renderer, ToolHost&) override { upload(renderer); }
  void draw(Renderer& renderer, ToolHost&, DrawLayer layer) override {
    if (layer == DrawLayer::Over) draw_bounds(renderer);
  }
  void window_title(std::string& title, const ToolHost&) const override { title += window_title(); }
  /// The scene (or `mode 2d`), structure, kernel and camera; a failed build's replay.
  void save_state(std::string& script, const ToolHost& host) const override;

  /// Starts with the lecture's binary BVH in the editor and an empty scene.
  StructureSession();

  /// Loads `spec` (OBJ path or procedural:NAME); on success it becomes the scene and its
  /// structure is rebuilt. On failure the old scene stays and the error is also shown.
  accel::Status load_scene(const std::string& spec);
  /// Loads `spec` on a background thread (the panel's Load button, dropped files): the old
  /// scene stays drawn and usable meanwhile, the panel shows the time taken and a Cancel
  /// button; poll() installs the result. Synchronous in script mode. A load asked for while
  /// one runs replaces it (the running one's result is dropped).
  void load_scene_in_background(const std::string& spec);
  /// Makes `scene` the scene, named `spec`, and rebuilds over it: the blackboard's 2D scenes.
  /// `edit`: the same scene changed (a triangle added, moved or deleted), so the camera and
  /// the debug ray stay (SessionEvents::scene_edited); otherwise a new scene (scene_loaded).
  void set_scene(accel::Scene scene, const std::string& spec, bool edit);
  /// Queues a load for the next poll() (drop callback: outside any ImGui frame).
  void request_load(std::string spec) { pending_loads_.push_back(std::move(spec)); }
  /// True while a background load runs.
  bool loading() const { return load_job_.busy(); }
  /// Drops the running background load (the old scene stays).
  void cancel_load();
  /// The memory budget of the structure builds (0: the default, half of physical memory);
  /// the current structure is rebuilt under it.
  void set_memory_limit(size_t bytes);
  /// Loads a preset's scene, its structure in the editor first when it names one.
  accel::Status load_preset_scene(const Preset& preset);
  /// Builds and scripts wait for each other (script mode) instead of running behind.
  void set_synchronous(bool synchronous) { synchronous_ = synchronous; }

  /// Runs the queued loads and takes a finished build (per frame, before the panels).
  void poll();
  /// The events since the last call.
  SessionEvents take_events();

  /// Shows structure `name` with `params` (the editor's kernel kept) and builds it. With a
  /// `build_call_limit` (a student's failed build replayed, construct-until) its builds stop
  /// after that many build-log calls until another structure is chosen: the build ends in an
  /// error that says it is the replay, and there is no structure to query.
  void switch_structure(const std::string& name, const std::vector<std::string>& params,
                        size_t build_call_limit = 0);
  /// Chooses the triangle kernel and rebuilds.
  void set_kernel(accel::Kernel kernel);
  /// Whether builds list a grid's empty cells (the node display asks for it).
  void set_empty_cells(bool on) { empty_cells_ = on; }
  /// Rebuilds from the editor's values.
  void rebuild() { request(editor_request()); }

  /// The scene shown.
  const accel::Scene& scene() const { return *scene_; }
  /// The scene, shared (jobs keep it alive).
  const std::shared_ptr<const accel::Scene>& scene_ptr() const { return scene_; }
  /// What was loaded last.
  const SceneInfo& scene_info() const { return scene_info_; }
  /// The structure built for the current scene, or nullptr (none yet, or an old scene's).
  const BuiltStructure* current() const { return matches_scene() ? built_.get() : nullptr; }
  /// current(), shared (for jobs).
  BuiltPtr current_ptr() const { return matches_scene() ? built_ : nullptr; }
  /// The structure drawn, even if for an old scene.
  const BuiltStructure* shown() const { return built_.get(); }
  /// The request of what is shown, or else of what is being built.
  StructureRequest current_request() const { return built_ ? built_->request : requested_; }
  /// The editor's request (with the node display's geometry options).
  StructureRequest editor_request() const;
  /// The registry entry in the editor.
  const accel::StructureInfo& editor_info() const { return editor_.info(); }
  /// Success, or why there is no structure for this scene (a build error first).
  accel::Status need_structure() const;
  /// The lecture presets.
  const std::vector<Preset>& presets() const { return presets_; }
  /// True while a build runs (or waits for a cancelled one to return).
  bool building() const { return builds_.busy(); }
  /// Seconds the running build has taken.
  double build_seconds() const { return builds_.seconds(); }
  /// Fraction of the running build done, from its BuildControl.
  double build_fraction() const { return builds_.fraction(); }
  /// The name being built.
  const std::string& requested_name() const { return requested_.name; }
  /// "accelviz - SCENE - STRUCTURE".
  std::string window_title() const;

  /// The Scene section; its camera buttons are returned (`has_saved_view` shows "Go to saved").
  SceneActions scene_section(bool has_saved_view);
  /// The Structure section: structure, kernel, parameters, build progress and statistics.
  void structure_section();

  /// Uploads a new scene's mesh to `renderer` (and its box lines) when needed.
  void upload(Renderer& renderer);
  /// Draws the scene's bounding box.
  void draw_bounds(Renderer& renderer) const;

 private:
  bool matches_scene() const { return built_ && built_->scene == scene_; }
  void request(const StructureRequest& request);
  void poll_build();
  void install(BuiltPtr built);
  void install_scene(const std::string& spec, accel::Result<accel::Scene> loaded, double load_ms);
  void poll_load();
  void memory_limit_widget();

  std::shared_ptr<const accel::Scene> scene_;
  SceneInfo scene_info_;
  ScenePanelState panel_;
  std::vector<std::string> pending_loads_;
  // The background load: its spec, whether it was replaced or cancelled (its result is then
  // dropped), and the load asked for meanwhile.
  Job<accel::Result<accel::Scene>> load_job_;
  std::string loading_spec_;
  bool load_dropped_ = false;
  std::optional<std::string> next_load_;
  std::string memory_limit_text_;  // the Structure section's field ("" = the default)
  std::string memory_limit_error_;
  std::vector<Preset> presets_;
  int preset_index_ = 0;  // the combo's entry; -1: the loaded scene is no preset
  ParamEditor editor_;
  bool empty_cells_ = false;
  BuiltPtr built_;
  BuildRunner builds_;
  StructureRequest requested_;  // the latest request (shown as "building")
  size_t build_call_limit_ = 0;  // a failed build's replay: the student structure's builds stop there
  std::string build_error_;
  bool synchronous_ = false;
  SessionEvents events_;
  bool scene_uploaded_ = false;  // false after a load until upload() ran
  std::optional<ColorBatch> bounds_lines_;
};

}  // namespace viz
