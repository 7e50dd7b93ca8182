#pragma once
// Small math vocabulary of the core: glm vectors, Ray, Aabb, BoundingSphere.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

/// Forces inlining of the few functions in the innermost traversal loops, which GCC would
/// otherwise keep out of line across the template layers.
#if defined(__GNUC__)
#define ACCEL_FORCE_INLINE inline __attribute__((always_inline))
#else
#define ACCEL_FORCE_INLINE inline
#endif

namespace accel {

using Vec3 = glm::vec3;
using DVec3 = glm::dvec3;
using UVec3 = glm::uvec3;

inline constexpr float kInf = std::numeric_limits<float>::infinity();

/// v[axis] for an axis known only at run time, as an indexed load. glm's operator[] is a
/// switch: in a traversal loop, where the axis changes per ray or per node, its branches
/// were mispredicted several times a ray (callgrind --branch-sim).
inline float component(const Vec3& v, int axis) { return glm::value_ptr(v)[axis]; }

/// A ray o + t*d, t in the closed interval [tmin, tmax] (docs/hits.md). d need not be unit length.
struct Ray {
  Vec3 org{0.0f};
  Vec3 dir{0.0f, 0.0f, 1.0f};
  float tmin = 0.0f;
  float tmax = kInf;
  Vec3 at(float t) const { return org + t * dir; }
};

/// Axis-aligned box. Default-constructed it is empty (min > max), so extend() starts it.
struct Aabb {
  Vec3 min{kInf};
  Vec3 max{-kInf};

  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  void extend(const Vec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
  void extend(const Aabb& b) { min = glm::min(min, b.min); max = glm::max(max, b.max); }
  Vec3 extent() const { return empty() ? Vec3(0.0f) : max - min; }
  Vec3 center() const { return 0.5f * (min + max); }
  /// Surface area; 0 for an empty box.
  float area() const {
    const Vec3 e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  float volume() const { const Vec3 e = extent(); return e.x * e.y * e.z; }
  int longest_axis() const {
    const Vec3 e = extent();
    return e.x >= e.y ? (e.x >= e.z ? 0 : 2) : (e.y >= e.z ? 1 : 2);
  }
  bool contains(const Aabb& b) const {
    return glm::all(glm::lessThanEqual(min, b.min)) && glm::all(glm::greaterThanEqual(max, b.max));
  }
};

// BoxTester reads an Aabb's bounds as six consecutive floats (min x y z, max x y z).
static_assert(sizeof(Vec3) == 3 * sizeof(float) && sizeof(Aabb) == 6 * sizeof(float));

/// Union of two boxes.
inline Aabb merge(const Aabb& a, const Aabb& b) { Aabb r = a; r.extend(b); return r; }

/// Bounding sphere (center, radius); radius < 0 means empty.
struct BoundingSphere {
  Vec3 center{0.0f};
  float radius = -1.0f;
  bool empty() const { return radius < 0.0f; }
};

}  // namespace accel
