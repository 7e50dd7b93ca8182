#pragma once
// Shared test data: scenes, ray sets and their reference answers, computed once per test
// binary (the double-precision reference is the slow part) and reused by every structure.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include <tbb/parallel_for.h>

#include "oracle.h"
#include "random.h"
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

/// Four small triangles in the planes x = 0, 1, 2, 3 (prims 0..3), 2 units tall. With
/// builder=median, axis=x, leaf_size=1 the flattened BVH is:
///   node 0 root {0,1,2,3}; node 1 {0,1}; node 2 leaf prim 0; node 3 leaf prim 1;
///   node 4 {2,3}; node 5 leaf prim 2; node 6 leaf prim 3.
inline Scene four_walls() {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (uint32_t k = 0; k < 4; ++k) {
    const float x = float(k);
    p.insert(p.end(), {{x, -1, -1}, {x, 1, -1}, {x, 0, 1}});
    t.emplace_back(3 * k, 3 * k + 1, 3 * k + 2);
  }
  return Scene(std::move(p), std::move(t));
}

/// Path of a mesh in ../shared/scenes (may not exist: callers skip).
inline std::string shared_scene_path(const std::string& file) {
  return std::string(ACCEL_SHARED_SCENES) + "/" + file;
}

/// Ray counts are multiplied by ACCEL_TEST_RAY_SCALE (default 1); the sanitizer run of
/// scripts/test.sh uses 0.1 because instrumented code is several times slower.
inline double ray_scale() {
  const char* s = std::getenv("ACCEL_TEST_RAY_SCALE");
  const double f = s ? std::atof(s) : 1.0;
  return f > 0.0 ? f : 1.0;
}
inline size_t scaled(size_t n) { return std::max<size_t>(1, size_t(double(n) * ray_scale())); }
/// An image side scaled so the pixel count scales like the ray count.
inline int scaled_side(int side) { return std::max(1, int(double(side) * std::sqrt(ray_scale()))); }

/// A ray o + t*d over [tmin, tmax], for hand-checked tests.
inline Ray make_ray(Vec3 org, Vec3 dir, float tmin = 0.0f, float tmax = kInf) {
  Ray r;
  r.org = org;
  r.dir = dir;
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

/// A recorded traversal as a compact event list: "push 0", "visit 2", "cull 1 missed",
/// "cull 4 beyond", "test 3 hit", "closest 3", "done 3" -- node ids and prims, no distances
/// (checked separately).
inline std::vector<std::string> trace_tokens(const TraceRecorder& rec) {
  std::vector<std::string> out;
  for (const TraceEvent& e : rec.events()) {
    const std::string n = std::to_string(e.node), p = std::to_string(e.prim);
    switch (e.kind) {
      case TraceEventKind::Push: out.push_back("push " + n); break;
      case TraceEventKind::Pop: out.push_back("pop " + n); break;
      case TraceEventKind::Visit: out.push_back("visit " + n); break;
      case TraceEventKind::EnterCell: out.push_back("enter " + n); break;
      case TraceEventKind::Cull:
        out.push_back("cull " + n + (e.reason == CullReason::MissedBounds ? " missed" : " beyond"));
        break;
      case TraceEventKind::TestPrim: out.push_back("test " + p + (e.hit ? " hit" : " miss")); break;
      case TraceEventKind::NewClosest: out.push_back("closest " + p); break;
      case TraceEventKind::Done: out.push_back("done " + p); break;
    }
  }
  return out;
}

/// The nodes a recorded traversal visited, in order.
inline std::vector<NodeId> visited(const TraceRecorder& rec) {
  std::vector<NodeId> ids;
  for (const TraceEvent& e : rec.events())
    if (e.kind == TraceEventKind::Visit) ids.push_back(e.node);
  return ids;
}

/// FNV-1a over raw bytes: identifies a scene + ray set for the reference cache.
inline uint64_t fnv1a(const void* data, size_t n, uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

/// Reference hits of `rays`, brute force in double. ctest runs every test in its own
/// process, so results are cached on disk (ACCEL_TEST_CACHE_DIR), keyed by a hash of the
/// scene and the rays, and written atomically so parallel tests may race harmlessly.
inline std::vector<ReferenceHit> reference_hits(const Scene& scene, const std::vector<Ray>& rays) {
  uint64_t h = fnv1a(scene.positions().data(), scene.positions().size() * sizeof(Vec3));
  h = fnv1a(scene.triangles().data(), scene.triangles().size() * sizeof(UVec3), h);
  h = fnv1a(rays.data(), rays.size() * sizeof(Ray), h);
  const std::filesystem::path dir(ACCEL_TEST_CACHE_DIR);
  const std::filesystem::path file = dir / (std::to_string(h) + ".ref");
  std::vector<ReferenceHit> ref(rays.size());
  {
    std::ifstream in(file, std::ios::binary);
    if (in && in.read(reinterpret_cast<char*>(ref.data()), std::streamsize(ref.size() * sizeof(ReferenceHit))) &&
        in.peek() == EOF)
      return ref;
  }
  tbb::parallel_for(size_t(0), rays.size(), [&](size_t i) { ref[i] = reference_closest(scene, rays[i]); });
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::filesystem::path tmp = file.string() + ".tmp" + std::to_string(h ^ uint64_t(::getpid()));
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(ref.data()), std::streamsize(ref.size() * sizeof(ReferenceHit)));
  }
  std::filesystem::rename(tmp, file, ec);
  return ref;
}

/// Random rays plus primary camera rays over a scene, with reference hits (cached by key
/// in memory, and on disk across test processes).
inline const Workload& workload(const std::string& key, const std::function<Scene()>& make_scene, size_t n_random,
                                int primary_w, int primary_h) {
  static std::map<std::string, std::unique_ptr<Workload>> cache;
  auto& slot = cache[key];
  if (!slot) {
    slot = std::make_unique<Workload>();
    slot->scene = make_scene();
    slot->rays = random_rays(slot->scene.bounds(), scaled(n_random), 12345);
    const auto primary =
        primary_rays(default_camera(slot->scene.bounds()), scaled_side(primary_w), scaled_side(primary_h));
    slot->rays.insert(slot->rays.end(), primary.begin(), primary.end());
    slot->reference = reference_hits(slot->scene, slot->rays);
  }
  return *slot;
}

/// Counts rays whose hit breaks docs/hits.md's rule; reports the first few.
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
