#pragma once
// The correctness rule of docs/hits.md, used by the tests (against a brute-force
// double reference) and by the benchmark's error columns.
#include <cmath>
#include <cstdint>
#include <string>

#include "geometry.h"
#include "scene.h"

namespace accel {

/// A reference closest hit: prim -1 for a miss, t in double precision.
struct ReferenceHit {
  int32_t prim = -1;
  double t = INFINITY;
};

/// How a returned hit compares with the reference.
enum class HitVerdict : uint8_t {
  Correct,    ///< same prim (or a tie) and t within tolerance
  FalseMiss,  ///< the reference hits, the answer misses
  FalseHit,   ///< the answer hits, the reference misses
  WrongPrim,  ///< t agrees but the triangle is neither the reference's nor tied with it
  WrongT,     ///< t differs beyond the tolerance and the ulp allowance
};
const char* verdict_name(HitVerdict v);

/// Brute-force closest hit with the double-precision kernel (the oracle); a 2D ray over a 2D
/// scene (Scene::planar()) by the 2D hit rule, PlanarRayTester: the 2D brute force.
ReferenceHit reference_closest(const Scene& scene, const Ray& ray);

/// Distance from p to triangle (a, b, c), in double.
double point_triangle_distance(const DVec3& p, const DVec3& a, const DVec3& b, const DVec3& c);

/// docs/hits.md's allowance: 8 float32 ulps of the scene's largest absolute coordinate M.
double ulp_allowance(const Scene& scene);

/// Judges `got` against `ref` by docs/hits.md's rule.
HitVerdict judge_hit(const Scene& scene, const Ray& ray, const Hit& got, const ReferenceHit& ref);

}  // namespace accel
