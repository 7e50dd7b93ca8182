#include "presets.h"

#include <filesystem>
#include <string_view>
#include <utility>

namespace viz {
namespace {

Preset basic(const char* name, std::string scene, const char* description, const char* structure = "") {
  Preset p;
  p.name = name;
  p.scene = std::move(scene);
  p.description = description;
  p.structure = structure;
  return p;
}

Preset with_view(Preset p, glm::vec3 eye, glm::vec3 target, float fovy, glm::vec3 ray_origin, glm::vec3 ray_target) {
  p.has_camera = true;
  p.eye = eye;
  p.target = target;
  p.fovy_deg = fovy;
  p.has_ray = true;
  p.ray_origin = ray_origin;
  p.ray_target = ray_target;
  return p;
}

}  // namespace

std::vector<Preset> lecture_presets(const std::string& source_dir) {
  namespace fs = std::filesystem;
  std::vector<Preset> out;
  // The ray starts at the eye and aims at a point of the object, so it is seen end-on
  // until the user orbits away to look at it from the side.
  out.push_back(with_view(basic("cornell", "procedural:cornell", "Cornell-like room: blocks and a ball"),
                          {0.2f, 1.15f, 3.6f}, {0.0f, 0.9f, 0.0f}, 45.0f, {0.2f, 1.15f, 3.6f}, {0.42f, 0.9f, 0.3f}));
  // Teapot in a stadium: the camera looks at the small dense object in the middle.
  out.push_back(with_view(basic("stadium", "procedural:stadium", "teapot in a stadium: small dense object, huge sparse room",
                                "grid"),
                          {2.4f, 1.7f, 3.2f}, {0.0f, 0.45f, 0.0f}, 40.0f, {2.4f, 1.7f, 3.2f}, {0.12f, 0.6f, 0.3f}));
  out.push_back(with_view(basic("sphere", "procedural:sphere", "icosphere, 5120 triangles"),
                          {1.9f, 1.3f, 2.7f}, {0.0f, 0.0f, 0.0f}, 45.0f, {1.9f, 1.3f, 2.7f}, {0.15f, 0.25f, 0.6f}));
  out.push_back(with_view(basic("soup", "procedural:soup", "10k random triangles in the unit cube"),
                          {2.1f, 1.7f, 2.5f}, {0.5f, 0.5f, 0.5f}, 45.0f, {2.1f, 1.7f, 2.5f}, {0.5f, 0.45f, 0.5f}));
  out.push_back(with_view(basic("terrain", "procedural:terrain", "1M-triangle heightfield (frame-rate test)"),
                          {0.85f, 0.55f, 0.95f}, {0.0f, 0.0f, 0.0f}, 45.0f, {0.85f, 0.55f, 0.95f},
                          {0.05f, 0.0f, 0.1f}));
  const fs::path root(source_dir);
  const fs::path steps = root / "scenes" / "steps.obj";
  if (fs::exists(steps)) {
    // The hand-checked ray of tests/cli: straight down onto the floor's tie edge region.
    out.push_back(with_view(basic("steps", steps.string(), "3 triangles: a split floor quad and a step (scenes/)", "brute"),
                            {3.6f, 2.8f, 5.0f}, {1.0f, 1.0f, 0.4f}, 45.0f, {0.25f, 0.25f, 5.0f},
                            {0.25f, 0.25f, 0.0f}));
  }
  // Real meshes (../shared/scenes): framed automatically, ray through the centre.
  for (const char* file : {"bunny.obj", "teapot.obj", "dragon_res4.obj", "sports_car.obj", "crytek_sponza.obj"}) {
    const fs::path p = root / ".." / "shared" / "scenes" / file;
    if (!fs::exists(p)) continue;
    Preset preset;
    preset.name = fs::path(file).stem().string();
    preset.scene = p.lexically_normal().string();
    preset.description = std::string("mesh ../shared/scenes/") + file;
    out.push_back(preset);
  }
  return out;
}

int preset_for_scene(const std::vector<Preset>& presets, const std::string& spec) {
  namespace fs = std::filesystem;
  for (size_t i = 0; i < presets.size(); ++i) {
    const std::string& scene = presets[i].scene;
    if (scene == spec) return static_cast<int>(i);
    // Files: "../shared/scenes/bunny.obj" and the preset's absolute path are the same file.
    std::error_code ec;
    if (!scene.starts_with("procedural:") && !spec.starts_with("procedural:") && fs::equivalent(scene, spec, ec) && !ec)
      return static_cast<int>(i);
  }
  return -1;
}

std::string scene_label(const std::string& spec) {
  constexpr std::string_view kProcedural = "procedural:";
  if (spec.starts_with(kProcedural)) return spec.substr(kProcedural.size());
  const std::string name = std::filesystem::path(spec).filename().string();
  return name.empty() ? "(file)" : name;
}

const Preset* find_preset(const std::vector<Preset>& presets, const std::string& name) {
  for (const Preset& p : presets)
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace viz
