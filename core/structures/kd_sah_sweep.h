#pragma once
// The kd-tree's SAH split search (lecture, kd-tree: "choose a splitting plane such that the
// expected costs of a ray test are minimal; try all 3 axes, search for the minimum along
// each axis, choose the axis and split position with the smallest minimum"): Wald & Havran
// 2006's sweep over a node's sorted events (kd_events.h), all three axes, O(N) per node.
#include <cstddef>
#include <vector>

#include "build_trace.h"
#include "structures/kd_builder.h"
#include "structures/kd_events.h"

namespace accel::kd {

/// The sweep's counts at one distinct event position (Wald & Havran's N_L, N_R, N_P): the
/// triangles starting or lying before it, ending or lying after it, lying in it.
struct PlaneCounts {
  float pos;  // the first event's position (its bits, -0 or +0, become the split's)
  uint32_t left, right, planar;
};

/// One thread's buffers for sah_split(), reused node after node, and what a recorded build
/// keeps of the node being split.
struct SahSweepScratch {
  std::vector<PlaneCounts> planes;  ///< the counts of one axis
  // Recording only (build_trace.h; untouched by the NullBuildSink build): whether the node
  // being split is recorded, and sah_split()'s planes of it with their costs, per axis swept.
  bool record = false;
  bool swept[3] = {false, false, false};
  std::vector<SplitCandidate> candidates[3];
  double best_cost = 0.0;  ///< the chosen plane's cost
};

/// Wald & Havran 2006, Algorithm 4 (per axis): sweep the sorted events; at each position p
/// the counts are N_L (triangles before), N_P (lying in p), N_R (after); the cost of a plane
/// is  lambda * (ct + ci * (A_L/A * N_L + A_R/A * N_R))  with the planar ones added to the
/// cheaper side, lambda = 1 - empty_bonus when a side is empty. Planes strictly inside the
/// region are candidates; a plane on its boundary only to cut off the triangles lying in it.
/// Returns "leaf" when no plane beats the leaf cost ci * N (Wald & Havran's automatic
/// termination).
/// Recording (Sink::kRecords and ws.record): every plane given a cost, in sweep order, per
/// axis into ws.candidates, and the chosen plane's cost into ws.best_cost.
/// Instantiated for NullBuildSink and BuildRecorder.
template <class Sink>
SplitChoice sah_split(const KdBuildOptions& o, SahSweepScratch& ws, const EventLists& events, const Aabb& box,
                      size_t n);

}  // namespace accel::kd
