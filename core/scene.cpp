#include "scene.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <utility>

#include "geometry.h"
#include "input_files.h"
#include "parallel.h"
#include "scene2d.h"

namespace accel {

Scene::Scene(std::vector<Vec3> positions, std::vector<UVec3> triangles, std::string name)
    : positions_(std::move(positions)), triangles_(std::move(triangles)), name_(std::move(name)) {
  for (const UVec3& t : triangles_)
    ACCEL_CHECK(t.x < positions_.size() && t.y < positions_.size() && t.z < positions_.size());
  compute_triangle_data();
}

Status Scene::move_vertices(std::span<const Vec3> positions) {
  if (positions.size() != positions_.size())
    return make_error("move_vertices: " + std::to_string(positions.size()) + " positions given, the scene has " +
                      std::to_string(positions_.size()) + " vertices");
  for (size_t i = 0; i < positions.size(); ++i) {
    const Vec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return make_error("move_vertices: vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
    if (planar_ && p.z != 0.0f)
      return make_error("move_vertices: vertex " + std::to_string(i) + " leaves the plane z = 0 of a 2D scene");
  }
  positions_.assign(positions.begin(), positions.end());
  compute_triangle_data();
  return {};
}

Status Scene::mark_planar() {
  for (size_t i = 0; i < positions_.size(); ++i)
    if (positions_[i].z != 0.0f)
      return make_error("2D scene: vertex " + std::to_string(i) + " has z = " + std::to_string(positions_[i].z) +
                        ", not 0");
  planar_ = true;
  return {};
}

void Scene::compute_triangle_data() {
  const size_t n = triangles_.size();
  tri_bounds_.resize(n);
  centroids_.resize(n);
  degenerate_.resize(n);
  // Per triangle in parallel (a moved scene is recomputed every animation frame); the
  // order-dependent parts, the ascending index list and the scene box, stay a sequential
  // pass in triangle order, so nothing depends on the thread count (not even the sign of a
  // zero bound: Aabb::extend keeps the first of two equal zeros).
  par::parallel_for(par::blocked_range<size_t>(0, n, 4096), [&](const par::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      const UVec3& t = triangles_[i];
      const Vec3 &a = positions_[t.x], &b = positions_[t.y], &c = positions_[t.z];
      Aabb box;
      box.extend(a);
      box.extend(b);
      box.extend(c);
      tri_bounds_[i] = box;
      centroids_[i] = box.center();
      degenerate_[i] = is_degenerate(a, b, c) ? 1 : 0;
    }
  });
  valid_prims_.clear();
  valid_prims_.reserve(n);
  bounds_ = Aabb{};
  for (size_t i = 0; i < n; ++i) {
    bounds_.extend(tri_bounds_[i]);
    if (!degenerate_[i]) valid_prims_.push_back(uint32_t(i));
  }
}

float Scene::max_abs_coordinate() const {
  if (bounds_.empty()) return 0.0f;
  const Vec3 m = glm::max(glm::abs(bounds_.min), glm::abs(bounds_.max));
  return std::max(m.x, std::max(m.y, m.z));
}

// Here rather than in mesh_loader.cpp: builds without Assimp (the web page) know the formats
// too, to say that they cannot read them.
bool is_mesh_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".ply" || ext == ".stl" || ext == ".gltf" || ext == ".glb";
}

namespace {
constexpr std::string_view kProceduralPrefix = "procedural:";
}  // namespace

Status fetch_scene_file(const std::string& spec) {
  if (spec.rfind(kProceduralPrefix, 0) == 0) return {};  // made here, not read
  return fetch_missing_input(spec);
}

Result<Scene> load_scene(const std::string& spec) {
  if (spec.rfind(kProceduralPrefix, 0) == 0)
    return make_procedural_scene(std::string_view(spec).substr(kProceduralPrefix.size()));
  if (Status fetched = fetch_missing_input(spec); !fetched) return fetched.error();  // the page: from its folder
  if (is_mesh_format(spec)) return load_mesh(spec);
  if (spec.size() > std::strlen(kScene2dExtension) && spec.ends_with(kScene2dExtension)) return load_scene2d(spec);
  return load_obj(spec);
}

}  // namespace accel
