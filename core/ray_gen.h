#pragma once
// Deterministic ray sets for tests and the benchmark, and the pinhole camera model shared
// by the viewer's picking, the heat map and primary-ray benchmarks.
#include <cstdint>
#include <string>
#include <vector>

#include "vec_math.h"
#include "result.h"
#include "scene.h"

namespace accel {

/// Pinhole camera looking from `eye` at `target`; `fovy_deg` is the vertical field of view.
struct PinholeCamera {
  Vec3 eye{0.0f, 0.0f, 5.0f};
  Vec3 target{0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float fovy_deg = 45.0f;
};

/// A camera that frames `bounds` from a fixed oblique direction (front, right, above).
PinholeCamera default_camera(const Aabb& bounds);

/// The ray through pixel (px, py) of a width x height image, pixel (0,0) at the top-left;
/// px, py may be fractional (pixel centres are at +0.5). Direction is normalised.
Ray camera_ray(const PinholeCamera& cam, float px, float py, int width, int height);

/// Primary rays through the centre of every pixel, row by row from the top-left.
std::vector<Ray> primary_rays(const PinholeCamera& cam, int width, int height);

/// `n` random rays for `scene` from `seed` (SplitMix64, random.h): origins uniform in the scene
/// box grown by 50% around its centre, directions towards a uniform point of the box (most
/// rays hit, many start inside the scene). `planar`: 2D rays, the same draws with z = 0.
std::vector<Ray> random_rays(const Aabb& bounds, size_t n, uint64_t seed, bool planar = false);

/// Parses a ray-set spec: "primary:W:H", "random:N:SEED", or a rays file path (docs/hits.md).
/// A 2D scene (Scene::planar()) takes 2D rays only: random ones in its plane, or a file
/// whose every ray is 2D (the error names the first that is not); primary rays are an error.
Result<std::vector<Ray>> make_rays(const std::string& spec, const Scene& scene);

}  // namespace accel
