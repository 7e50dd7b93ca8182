#pragma once
// ImGui panels, one function each (imgui_demo's ShowDemoWindow...() habit). A panel
// reads plain data and returns what the user asked for; App carries the requests out,
// so panels never touch the scene or GL themselves.
#include <optional>
#include <string>
#include <vector>

#include "math.h"

namespace viz {

/// What the scene panel shows about the loaded scene.
struct SceneInfo {
  std::string spec;        ///< as loaded: a path or "procedural:NAME"
  std::string name;        ///< Scene::name()
  size_t triangles = 0;
  size_t vertices = 0;
  size_t degenerate = 0;
  accel::Aabb bounds;
  double load_ms = 0.0;    ///< wall time of accel::load_scene
};

/// Frame timing, smoothed by App so the numbers are readable.
struct FrameTiming {
  double frame_ms = 0.0;
  double fps = 0.0;
};

/// Mutable UI state of the scene panel, owned by App.
struct ScenePanelState {
  std::string obj_path;                   ///< the "Load OBJ" text field
  std::vector<std::string> presets;       ///< procedural scene names for the preset combo
  int preset = 0;                         ///< index into presets
  std::string load_error;                 ///< last load error (shown in red), empty if none
};

/// Requests from the scene panel, carried out by App after the frame's UI is built.
struct ScenePanelActions {
  std::optional<std::string> load;  ///< scene spec to load (OBJ path or "procedural:NAME")
  bool frame_scene = false;         ///< reset the camera to frame the scene bounds
};

/// The "Scene" window: statistics, timing, OBJ/procedural loading, the last load error
/// and a short mouse help. Call between ImGui::NewFrame() and ImGui::Render().
ScenePanelActions scene_panel(const SceneInfo& scene, const FrameTiming& timing,
                              ScenePanelState& state);

}  // namespace viz
