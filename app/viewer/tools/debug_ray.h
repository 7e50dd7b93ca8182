#pragma once
// GL-free half of the ray debugger (tools/ray_debugger.h is the tool): the debug ray, its
// traversal recorded by the structure's real intersect_traced, the kit's audit of that
// walk for a student's structure, and where to draw its end.
// tests/app/test_ray_debugger.cpp drives it without a window.
#include <optional>
#include <string>
#include <vector>

#include "geometry.h"
#include "structure.h"
#include "student/walk_audit.h"
#include "trace.h"
#include "trace_player.h"

namespace viz {

/// The ray being debugged and its recorded traversal.
struct DebugRay {
  bool active = false;
  accel::Ray ray;
  std::string origin;          ///< how it was made: "click", "typed", "preset", "script"
  accel::Hit hit;              ///< intersect_traced's answer
  accel::QueryStats stats;     ///< counters of the whole trace
  accel::TracePlayer player;
  /// The loop's variables recorded with the trace (grid, kd-tree, octree); see vars_at().
  std::vector<accel::RecordedVars> vars;
  /// The traversal made more steps than the recorder's budget keeps: the player has the
  /// first ones and the answer; `stats` count the whole traversal all the same.
  bool truncated = false;
  /// A student's structure (accel::KitStructure): every claim of its traversal log checked
  /// against the geometry, once per recording (tools/false_claims.h shows the false ones).
  /// Nothing for a built-in structure: its walk is the core's own and is never audited.
  std::optional<accel::WalkAudit> audit;

  /// Records the ray's traversal of `s` (its real intersect_traced). keep_step: the same ray
  /// replayed after a rebuild keeps its step, clamped. `scene`: the scene `s` was built over;
  /// with it a student's walk is audited (without it, not).
  void record(const accel::Structure& s, bool keep_step, const accel::Scene* scene = nullptr);
};

/// The ray's end point for drawing: the hit, or where it leaves `bounds` (grown a little),
/// or a fallback length when it misses the scene box entirely.
float ray_draw_length(const accel::Ray& ray, const accel::Hit& hit, const accel::Aabb& bounds);

}  // namespace viz
