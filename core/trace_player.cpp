#include "trace_player.h"

#include <algorithm>
#include <cmath>

namespace accel {

// ---------------------------------------------------------------------------------------
// TracePlayer

void TracePlayer::load(std::vector<TraceEvent> events, bool keep_step) {
  events_ = std::move(events);
  if (keep_step)
    resize(events_.size());
  else
    restart(events_.size());
}

bool TracePlayer::jump_to_hit() {
  pause();
  return seek(hit_step());
}

size_t TracePlayer::hit_step() const {
  if (events_.empty()) return 0;
  size_t done = events_.size() - 1;
  for (size_t i = events_.size(); i-- > 0;) {
    if (events_[i].kind == TraceEventKind::Done) {
      done = i;
      break;
    }
  }
  const TraceEvent& d = events_[done];
  if (d.kind != TraceEventKind::Done || !d.hit) return done;
  // The final answer was set by exactly one NewClosest (a later one would have replaced it).
  for (size_t i = 0; i < done; ++i)
    if (events_[i].kind == TraceEventKind::NewClosest && events_[i].prim == d.prim) return i;
  return done;
}

// ---------------------------------------------------------------------------------------
// Highlight state

namespace {

void remove_pending(std::vector<PendingNode>& pending, NodeId node) {
  // Search from the back: on a stack the popped node is the last one.
  for (size_t i = pending.size(); i-- > 0;) {
    if (pending[i].node == node) {
      pending.erase(pending.begin() + std::ptrdiff_t(i));
      return;
    }
  }
}

}  // namespace

TraceHighlight trace_highlight(std::span<const TraceEvent> events, size_t step) {
  TraceHighlight h;
  if (events.empty()) return h;
  h.valid = true;
  h.step = std::min(step, events.size() - 1);
  h.event = events[h.step];
  for (size_t i = 0; i <= h.step; ++i) {
    const TraceEvent& e = events[i];
    switch (e.kind) {
      case TraceEventKind::Visit:
      case TraceEventKind::EnterCell:
        h.node = e.node;
        h.node_depth = e.depth;
        h.t0 = e.t0;
        h.t1 = e.t1;
        h.node_step = i;
        h.tested.clear();
        h.visited.push_back(e.node);
        ++h.counters.nodes_visited;
        break;
      case TraceEventKind::Cull:
        h.culled.push_back({e.node, e.depth, e.reason, e.t0, i});
        // A pending node skipped without a pop (the priority queue's final sweep) leaves it.
        remove_pending(h.pending, e.node);
        ++h.counters.nodes_culled;
        break;
      case TraceEventKind::Push:
        h.pending.push_back({e.node, e.depth, e.t0});
        h.counters.max_stack = std::max<uint64_t>(h.counters.max_stack, h.pending.size());
        break;
      case TraceEventKind::Pop:
        remove_pending(h.pending, e.node);
        break;
      case TraceEventKind::TestPrim:
        h.tested.push_back({e.prim, e.hit, e.hit ? e.t0 : kInf});
        ++h.counters.prims_tested;
        break;
      case TraceEventKind::NewClosest:
        h.closest_prim = e.prim;
        h.closest_t = e.t0;
        break;
      case TraceEventKind::Done:
        h.done = true;
        h.closest_prim = e.prim;
        h.closest_t = e.hit ? e.t0 : kInf;
        break;
    }
  }
  return h;
}

std::vector<PendingNode> sorted_by_key(std::vector<PendingNode> pending) {
  std::stable_sort(pending.begin(), pending.end(), [](const PendingNode& a, const PendingNode& b) {
    return a.key < b.key || (a.key == b.key && a.node < b.node);
  });
  return pending;
}

}  // namespace accel
