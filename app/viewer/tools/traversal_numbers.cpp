#include "tools/traversal_numbers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <variant>

namespace viz {
namespace {

std::string number(float v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
  return buf;
}

}  // namespace

bool keeps_pending(TraversalKind kind) {
  switch (kind) {
    case TraversalKind::Octree:
    case TraversalKind::KdTree:
    case TraversalKind::HierarchyDfs:
    case TraversalKind::HierarchyOrdered:
    case TraversalKind::HierarchyPqueue: return true;
    case TraversalKind::Brute:
    case TraversalKind::Grid:
    case TraversalKind::Grid2d:
    case TraversalKind::Unknown: return false;
  }
  return false;
}

std::vector<accel::PendingNode> pending_in_pop_order(const accel::TraceHighlight& highlight, TraversalKind kind) {
  if (kind == TraversalKind::HierarchyPqueue) return accel::sorted_by_key(highlight.pending);
  // A stack pops its last push first.
  return {highlight.pending.rbegin(), highlight.pending.rend()};
}

std::string vars_line(std::span<const accel::RecordedVars> vars, std::span<const accel::TraceEvent> events,
                      const accel::TraceHighlight& highlight, TraversalKind kind) {
  std::string line = "vars:";
  // Appended piece by piece: GCC 12's -Wrestrict misfires on "literal" + std::string here.
  if (const accel::StepVars* v = accel::vars_at(events, vars, highlight.step)) {
    line += ' ';
    line += accel::describe_vars(*v);
  }
  line += " closest_hit=";
  line += number(highlight.closest_t);
  if (keeps_pending(kind)) {
    line += kind == TraversalKind::HierarchyPqueue ? " queue=" : " stack=";
    const std::vector<accel::PendingNode> pending = pending_in_pop_order(highlight, kind);
    if (pending.empty()) line += "-";
    for (size_t i = 0; i < pending.size(); ++i) {
      if (i > 0) line += ',';
      line += std::to_string(pending[i].node);
      line += ':';
      line += number(pending[i].key);
    }
  }
  return line;
}

void t_strip_range(std::span<const accel::TraceEvent> events, float tmin, float& t_lo, float& t_hi) {
  t_lo = std::isfinite(tmin) ? tmin : 0.0f;
  float far = -accel::kInf, first = accel::kInf;  // the farthest distance, the first entry
  for (const accel::TraceEvent& e : events)
    if ((e.kind == accel::TraceEventKind::Visit || e.kind == accel::TraceEventKind::EnterCell) && std::isfinite(e.t0))
      first = std::min(first, e.t0);
  auto grow = [&](float t) {
    if (std::isfinite(t)) far = std::max(far, t);
  };
  for (const accel::TraceEvent& e : events) {
    switch (e.kind) {
      case accel::TraceEventKind::Visit:
      case accel::TraceEventKind::EnterCell: grow(e.t1); break;
      case accel::TraceEventKind::TestPrim:
        if (e.hit) grow(e.t0);
        break;
      case accel::TraceEventKind::Push:
      case accel::TraceEventKind::Pop:
      case accel::TraceEventKind::Cull:
      case accel::TraceEventKind::NewClosest:
      case accel::TraceEventKind::Done: grow(e.t0); break;
    }
  }
  t_hi = far > t_lo ? far : t_lo + 1.0f;
  // A ray that starts far from the scene would squeeze every interval into the right end:
  // the axis then starts a little before the first entry instead of at tmin.
  if (std::isfinite(first) && first > t_lo && first < t_hi) t_lo = std::max(t_lo, first - 0.08f * (t_hi - first));
}

TStrip t_strip_at(std::span<const accel::TraceEvent> events, std::span<const accel::RecordedVars> vars,
                  const accel::TraceHighlight& h, float t_lo, float t_hi) {
  TStrip s;
  s.t_lo = t_lo;
  s.t_hi = t_hi;
  if (events.empty() || !h.valid) return s;
  const size_t step = std::min(h.step, events.size() - 1);
  for (size_t i = 0; i <= step; ++i) {
    const accel::TraceEvent& e = events[i];
    if (e.kind == accel::TraceEventKind::Visit || e.kind == accel::TraceEventKind::EnterCell)
      s.intervals.push_back({e.t0, e.t1, i == h.node_step});
    else if (e.kind == accel::TraceEventKind::Push)
      s.keys.push_back({e.t0, false});
  }
  // The keys still pending are the highlight's pending set (push order kept there too).
  for (const accel::PendingNode& p : h.pending)
    for (auto it = s.keys.rbegin(); it != s.keys.rend(); ++it)
      if (!it->pending && it->t == p.key) {
        it->pending = true;
        break;
      }
  for (const accel::RecordedVars& r : vars) {
    if (r.event > step) break;
    const bool current = r.event >= h.node_step;
    if (const auto* kd = std::get_if<accel::KdSplitVars>(&r.vars)) s.splits.push_back({kd->t_split, current});
    else if (const auto* ex = std::get_if<accel::KdExitVars>(&r.vars)) s.splits.push_back({ex->t_split, current});
  }
  s.closest = h.closest_t;
  const accel::TraceEvent& e = events[step];
  const bool has_t = (e.kind == accel::TraceEventKind::TestPrim && e.hit) || e.kind == accel::TraceEventKind::Push ||
                     e.kind == accel::TraceEventKind::Pop || e.kind == accel::TraceEventKind::NewClosest;
  if (has_t) s.event_t = e.t0;
  return s;
}

}  // namespace viz
