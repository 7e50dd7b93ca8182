#include "tools/debug_ray.h"

#include <cmath>

#include "student/kit_structure.h"

namespace viz {

void DebugRay::record(const accel::Structure& s, bool keep_step, const accel::Scene* scene) {
  accel::TraceRecorder recorder;
  hit = s.intersect_traced(ray, recorder);
  truncated = recorder.truncated();
  // A truncated recording lacks steps to count: the same query through the counting sink.
  if (truncated)
    s.intersect(ray, &stats);
  else
    stats = recorder.stats();
  vars = recorder.recorded_vars();
  // The audit reads the recorded walk once here, with the trace, never per frame: its
  // lossy check is one brute-force pass over the scene (find_lossy), worth it for one ray.
  audit.reset();
  if (const auto* kit = dynamic_cast<const accel::KitStructure*>(&s); kit && scene) {
    const accel::WalkAuditor auditor(kit->tree(), kit->kind(), *scene);
    audit = auditor.audit(ray, recorder.events(), vars, /*find_lossy=*/true);
  }
  player.load(recorder.events(), keep_step);
}

float ray_draw_length(const accel::Ray& ray, const accel::Hit& hit, const accel::Aabb& bounds) {
  if (hit.valid()) return hit.t;
  const float diag = bounds.empty() ? 1.0f : glm::length(bounds.extent());
  accel::Aabb grown = bounds;
  if (!grown.empty()) {
    grown.min -= glm::vec3(0.05f * diag);
    grown.max += glm::vec3(0.05f * diag);
  }
  const accel::BoxTester tester(ray);
  float t0 = 0.0f, t1 = 0.0f;
  const float len = glm::length(ray.dir);
  if (!grown.empty() && tester.intersect(grown, ray.tmin, accel::kInf, &t0, &t1) && std::isfinite(t1)) return t1;
  return len > 0.0f ? 2.0f * diag / len : 1.0f;
}

}  // namespace viz
