#include "scene.h"

#include <utility>

#include "geometry.h"

namespace accel {

Scene::Scene(std::vector<Vec3> positions, std::vector<UVec3> triangles, std::string name)
    : positions_(std::move(positions)), triangles_(std::move(triangles)), name_(std::move(name)) {
  const size_t n = triangles_.size();
  tri_bounds_.resize(n);
  centroids_.resize(n);
  degenerate_.resize(n);
  valid_prims_.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const UVec3& t = triangles_[i];
    ACCEL_CHECK(t.x < positions_.size() && t.y < positions_.size() && t.z < positions_.size());
    const Vec3 &a = positions_[t.x], &b = positions_[t.y], &c = positions_[t.z];
    Aabb box;
    box.extend(a);
    box.extend(b);
    box.extend(c);
    tri_bounds_[i] = box;
    centroids_[i] = box.center();
    bounds_.extend(box);
    degenerate_[i] = is_degenerate(a, b, c) ? 1 : 0;
    if (!degenerate_[i]) valid_prims_.push_back(uint32_t(i));
  }
}

float Scene::max_abs_coordinate() const {
  if (bounds_.empty()) return 0.0f;
  const Vec3 m = glm::max(glm::abs(bounds_.min), glm::abs(bounds_.max));
  return std::max(m.x, std::max(m.y, m.z));
}

Result<Scene> load_scene(const std::string& spec) {
  constexpr std::string_view prefix = "procedural:";
  if (spec.rfind(prefix, 0) == 0) return make_procedural_scene(std::string_view(spec).substr(prefix.size()));
  return load_obj(spec);
}

}  // namespace accel
