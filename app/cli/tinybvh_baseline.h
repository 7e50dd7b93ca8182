#pragma once
// tinybvh (jbikker/tinybvh, single header) as the second peer of `accelviz-cli bench`: the
// same scene and rays through its fastest CPU layouts, BVH8_CPU (AVX2) and BVH4_CPU (SSE4.2).
// Compiled only when CMake finds tiny_bvh.h (ACCEL_TINYBVH_DIR); otherwise tinybvh_available()
// is false and the bench has no tinybvh rows.
//
// tinybvh_baseline.cpp is compiled with -mavx2 -mfma (BVH8_CPU needs them, and tinybvh's
// implementation lives in one translation unit), so every call into this class may execute
// AVX2 code: callers check tinybvh_cpu_supported() first. That is why this header only uses
// plain types: the AVX2 unit includes no accelviz header whose inline functions the linker
// could pick for the rest of the program.
#include <cstddef>
#include <cstdint>
#include <memory>

namespace cli {

/// True when this binary was built with tinybvh.
bool tinybvh_available();

/// True when this CPU runs the tinybvh unit's code (AVX2 and FMA). Defined in bench.cpp,
/// which is compiled without -mavx2.
bool tinybvh_cpu_supported();

/// Which tinybvh layout and builder.
enum class TinyBvhLayout {
  Bvh8,    ///< BVH8_CPU over the binned SAH build (BVH::BuildDefault = BuildAVX, then 8-wide)
  Bvh4,    ///< BVH4_CPU over the same binned build, 4-wide
  Bvh8Hq,  ///< BVH8_CPU over BuildHQ (SBVH: spatial splits)
};

/// A closest hit as tinybvh reports it: prim = -1 for a miss.
struct TinyBvhHit {
  int32_t prim = -1;
  float t = 0.0f, u = 0.0f, v = 0.0f;
};

/// A tinybvh BVH over an accelviz scene's triangles (in the scene's order, so tinybvh's prim
/// index is the scene's triangle number; degenerate triangles are passed on as they are).
class TinyBvhScene {
 public:
  /// triangles: 9 floats per triangle (v0, v1, v2). Copied into tinybvh's bvhvec4 array,
  /// which the BVH keeps pointing to. tinybvh's builders start their own std::threads.
  TinyBvhScene(const float* triangles, size_t triangle_count, TinyBvhLayout layout);
  ~TinyBvhScene();
  TinyBvhScene(const TinyBvhScene&) = delete;
  TinyBvhScene& operator=(const TinyBvhScene&) = delete;

  /// Wall time of Build/BuildHQ (the binned or spatial-split build, the collapse to 4 or 8
  /// wide and the conversion to the traversal layout); the vertex copy is not timed.
  double build_ms() const { return build_ms_; }
  /// Bytes of the traversal layout (nodes and triangle leaves, usedBlocks x 64 B); the
  /// intermediate binary and wide BVHs tinybvh keeps beside it are not counted.
  size_t memory_bytes() const;
  /// Closest hit in [0, tmax] (tinybvh has no tmin: the caller decides what a ray with
  /// tmin > 0 means). tmax = inf is passed as tinybvh's 1e30. dir is used as given (not
  /// normalised), so t is in the ray's own units like accelviz's.
  TinyBvhHit intersect(const float org[3], const float dir[3], float tmax) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double build_ms_ = 0.0;
};

}  // namespace cli
