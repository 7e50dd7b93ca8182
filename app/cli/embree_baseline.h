#pragma once
// Embree 3 as the industry baseline of `accelviz-cli bench`: the same scene and rays through
// rtcIntersect1, at build quality medium or high. Compiled only when libembree-dev is present
// (ACCEL_HAVE_EMBREE); otherwise embree_available() is false and the bench leaves the column empty.
#include <memory>
#include <string>
#include <vector>

#include "geometry.h"
#include "scene.h"

namespace cli {

/// True when this binary was built with Embree.
bool embree_available();

/// An Embree scene built from an accelviz Scene (degenerate triangles included: Embree
/// skips them itself, and prim ids stay the scene's triangle numbers).
class EmbreeScene {
 public:
  /// quality: "medium", "high", or "robust" (medium with RTC_SCENE_FLAG_ROBUST: Embree's
  /// mode that avoids optimisations which lose hits at edges, at some cost in speed).
  /// threads: Embree's build threads (0 = all cores), so its build time compares with ours
  /// at the bench's thread count.
  EmbreeScene(const accel::Scene& scene, const std::string& quality, int threads = 0);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// Wall time of the build: rtcNewScene, the geometry's buffers filled and committed, and
  /// rtcCommitScene (the device is made before the clock starts: it is not per scene).
  double build_ms() const { return build_ms_; }
  /// Bytes Embree allocated for this scene (its memory monitor callback).
  size_t memory_bytes() const;
  /// Closest hit via rtcIntersect1 (prim = Embree's primID, t = tfar, u, v its barycentrics).
  accel::Hit intersect(const accel::Ray& ray) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double build_ms_ = 0.0;
};

}  // namespace cli
