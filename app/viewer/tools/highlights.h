#pragma once
// GL-free: what the debug ray's current trace step looks like in 3D (the ray, the current
// node and its interval, trail, skipped and pending nodes, tested triangles, the hit), as
// plain vertex lists the ray debugger uploads. Owns nothing.
#include <vector>

#include "built_structure.h"
#include "structure_view.h"
#include "tools/debug_ray.h"

namespace viz {

/// Which optional parts the highlights include (the Display section's checkboxes).
struct HighlightOptions {
  bool trail = true;    ///< nodes visited before the current one
  bool culled = true;   ///< nodes skipped so far
  bool pending = true;  ///< nodes on the stack / priority queue
};

/// The highlights of one step, ready to upload.
struct Highlights {
  std::vector<Segment> segments;       ///< thick: ray, current node, tested triangles' outlines
  std::vector<ColorVertex> triangles;  ///< filled: tested and closest triangles, split plane
  std::vector<ColorVertex> lines;      ///< thin: trail, culled and pending nodes
  accel::TraceHighlight step;          ///< accel::trace_highlight of the current step
  int code_line = -1;                  ///< pseudo-code line of the current step (-1: none)
};

/// The highlights of `ray` at its player's current step. `built` is the structure the
/// trace was recorded on, or nullptr when there is none for `scene` (then only the ray
/// and its hit are drawn). Nothing when the ray is not active.
Highlights build_highlights(const DebugRay& ray, const accel::Scene& scene, const BuiltStructure* built,
                            const HighlightOptions& options);

}  // namespace viz
