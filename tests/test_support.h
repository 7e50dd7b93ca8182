#pragma once
// Shared test data: scenes, ray sets and their reference answers, computed once per test
// binary (the double-precision reference is the slow part) and reused by every structure.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "oracle.h"
#include "ray_gen.h"
#include "scene.h"
#include "structure.h"

namespace accel::testing {

/// A scene with rays and the reference closest hit of each ray.
struct Workload {
  Scene scene;
  std::vector<Ray> rays;
  std::vector<ReferenceHit> reference;
};

/// Path of a mesh in ../shared/scenes (may not exist: callers skip).
inline std::string shared_scene_path(const std::string& file) {
  return std::string(ACCEL_SHARED_SCENES) + "/" + file;
}

/// Random rays plus primary camera rays over `scene`, with reference hits (cached by key).
inline const Workload& workload(const std::string& key, const std::function<Scene()>& make_scene, size_t n_random,
                                int primary_w, int primary_h) {
  static std::map<std::string, std::unique_ptr<Workload>> cache;
  auto& slot = cache[key];
  if (!slot) {
    slot = std::make_unique<Workload>();
    slot->scene = make_scene();
    slot->rays = random_rays(slot->scene.bounds(), n_random, 12345);
    const auto primary = primary_rays(default_camera(slot->scene.bounds()), primary_w, primary_h);
    slot->rays.insert(slot->rays.end(), primary.begin(), primary.end());
    slot->reference.resize(slot->rays.size());
    tbb::parallel_for(size_t(0), slot->rays.size(), [&](size_t i) {
      slot->reference[i] = reference_closest(slot->scene, slot->rays[i]);
    });
  }
  return *slot;
}

/// Counts rays whose hit breaks formats.md's rule; reports the first few.
inline size_t count_wrong(const Workload& w, const std::vector<Hit>& hits, std::string* first_failures) {
  size_t wrong = 0;
  for (size_t i = 0; i < hits.size(); ++i) {
    std::string why;
    if (!hit_is_correct(w.scene, w.rays[i], hits[i], w.reference[i], &why)) {
      if (++wrong <= 5 && first_failures) *first_failures += "ray " + std::to_string(i) + ": " + why + "\n";
    }
  }
  return wrong;
}

}  // namespace accel::testing
