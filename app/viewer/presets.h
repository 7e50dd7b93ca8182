#pragma once
// Lecture presets: a scene with a saved camera and a saved debug ray, so each demo starts
// from the same view every time. A small table; meshes from ../shared/scenes only appear
// when the file exists. GL-free.
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace viz {

struct Preset {
  std::string name;         ///< shown in the combo and taken by the `preset` script command
  std::string scene;        ///< "procedural:NAME" or an OBJ path
  std::string description;
  bool has_camera = false;  ///< false: frame the scene instead
  glm::vec3 eye{0.0f}, target{0.0f};
  float fovy_deg = 45.0f;
  bool has_ray = false;     ///< false: shoot through the centre of the view
  glm::vec3 ray_origin{0.0f}, ray_target{0.0f};  ///< the saved ray: from origin towards target
  std::string structure;    ///< structure to switch to ("" = keep the current one)
};

/// The presets whose scene is available. `source_dir` is the repository root (scenes/ and
/// ../shared/scenes are looked up from it).
std::vector<Preset> lecture_presets(const std::string& source_dir);

/// The index of the preset whose scene is `spec` (the same file, however the path is
/// spelled), or -1 when none is.
int preset_for_scene(const std::vector<Preset>& presets, const std::string& spec);

/// What the scene combo shows for a scene that is no preset: the file's name
/// ("bunny.obj"), or the procedural scene's ("procedural:NAME" -> "NAME").
std::string scene_label(const std::string& spec);

/// The preset named `name` in `presets`, or nullptr.
const Preset* find_preset(const std::vector<Preset>& presets, const std::string& name);

}  // namespace viz
