// The kd-tree's SAH sweep (lecture, kd-tree: "try all 3 axes, search for the minimum along
// each axis, choose the axis / split position with the smallest minimum"): Wald & Havran 2006,
// "On building fast kd-trees for ray tracing, and on doing that in O(N log N)", Algorithm 4,
// over the sorted events of kd_events.h.
#include "structures/kd_sah_sweep.h"

#include <algorithm>
#include <cmath>

namespace accel::kd {
namespace {

/// The counts at every distinct position of the sorted `events` of a node of `n` triangles,
/// into `planes` (grown as needed); returns how many. Without a branch per event: positions
/// shared by a few events (mesh vertices) make "same position as the next?" random, so every
/// event writes the running counts and only the last one of a position advances the output.
size_t count_planes(const std::vector<Event>& events, size_t n, std::vector<PlaneCounts>& planes) {
  const size_t count = events.size();
  if (planes.size() < count) planes.resize(count);
  if (count == 0) return 0;
  const Event* ev = events.data();
  PlaneCounts* out = planes.data();
  uint32_t before = 0, starts_planars = 0, ends_planars = 0, planars = 0;  // before = of earlier positions
  float first = ev[0].pos;
  size_t g = 0;
  for (size_t i = 0; i < count; ++i) {
    const uint32_t type = ev[i].type();
    starts_planars += type != kEnd;
    ends_planars += type != kStart;
    planars += type == kPlanar;
    out[g] = {first, before, uint32_t(n) - ends_planars, planars};
    const float next = i + 1 < count ? ev[i + 1].pos : first;
    const bool last = i + 1 == count || !(next == ev[i].pos);
    g += last;
    before = last ? starts_planars : before;
    planars = last ? 0 : planars;
    first = last ? next : first;
  }
  return g;
}

}  // namespace

template <class Sink>
SplitChoice sah_split(const KdBuildOptions& o, SahSweepScratch& ws, const EventLists& events, const Aabb& box,
                      size_t n) {
  SplitChoice best;
  const DVec3 e = DVec3(box.max) - DVec3(box.min);
  const double area = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
  if (!(area > 0.0)) return best;
  const double inv_area = 1.0 / area;
  double best_cost = o.ci * double(n);
  auto cost = [&](double pl, double pr, size_t nl, size_t nr) {
    const double c = o.ct + o.ci * (pl * double(nl) + pr * double(nr));
    return (nl == 0 || nr == 0) ? c * (1.0 - o.empty_bonus) : c;
  };
  for (int axis = 0; axis < 3; ++axis) {
    if (!(box.max[axis] > box.min[axis])) continue;
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const double cross = e[a1] * e[a2], around = e[a1] + e[a2];
    const size_t planes = count_planes(events.axis[axis], n, ws.planes);
    if constexpr (Sink::kRecords) {
      if (ws.record) {
        ws.swept[axis] = true;
        ws.candidates[axis].clear();
      }
    }
    for (size_t g = 0; g < planes; ++g) {
      const float p = ws.planes[g].pos;
      const size_t nl = ws.planes[g].left, nr = ws.planes[g].right, planars = ws.planes[g].planar;
      const double dl = double(p) - double(box.min[axis]), dr = double(box.max[axis]) - double(p);
      const double pl = 2.0 * (cross + dl * around) * inv_area, pr = 2.0 * (cross + dr * around) * inv_area;
      if (p > box.min[axis] && p < box.max[axis]) {
        // Without planars both sides cost the same (and planar_left stays true).
        const double c_left = cost(pl, pr, nl + planars, nr);
        const double c_right = planars > 0 ? cost(pl, pr, nl, nr + planars) : c_left;
        const double c = std::min(c_left, c_right);
        if constexpr (Sink::kRecords) {
          if (ws.record)
            ws.candidates[axis].push_back(c_left <= c_right ? SplitCandidate{p, float(c), uint32_t(nl + planars), uint32_t(nr)}
                                                            : SplitCandidate{p, float(c), uint32_t(nl), uint32_t(nr + planars)});
        }
        if (c < best_cost) {
          best_cost = c;
          best = {axis, p, c_left <= c_right};
        }
      } else if (planars > 0 && planars < n) {
        // A plane on the region's boundary holding planar triangles: cut them off into a
        // flat cell (Wald & Havran 2006 sec. 4.4), e.g. the walls of axis-aligned rooms.
        // Both sides then hold fewer triangles than the node, so this always progresses.
        const bool at_min = p == box.min[axis];
        const double c = at_min ? cost(pl, pr, planars, n - planars) : cost(pl, pr, n - planars, planars);
        if constexpr (Sink::kRecords) {
          if (ws.record)
            ws.candidates[axis].push_back(at_min ? SplitCandidate{p, float(c), uint32_t(planars), uint32_t(n - planars)}
                                                 : SplitCandidate{p, float(c), uint32_t(n - planars), uint32_t(planars)});
        }
        if (c < best_cost) {
          best_cost = c;
          best = {axis, p, at_min};
        }
      }
    }
  }
  if constexpr (Sink::kRecords) ws.best_cost = best_cost;
  return best;
}

template SplitChoice sah_split<NullBuildSink>(const KdBuildOptions&, SahSweepScratch&, const EventLists&, const Aabb&,
                                              size_t);
template SplitChoice sah_split<BuildRecorder>(const KdBuildOptions&, SahSweepScratch&, const EventLists&, const Aabb&,
                                              size_t);

}  // namespace accel::kd
