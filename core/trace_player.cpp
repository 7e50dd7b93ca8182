#include "trace_player.h"

#include <algorithm>
#include <cmath>

namespace accel {

// ---------------------------------------------------------------------------------------
// TracePlayer

void TracePlayer::load(std::vector<TraceEvent> events, bool keep_step) {
  events_ = std::move(events);
  if (!keep_step) {
    reset();
    return;
  }
  step_ = events_.empty() ? 0 : std::min(step_, events_.size() - 1);
  if (at_end()) playing_ = false;
}

void TracePlayer::clear() {
  events_.clear();
  reset();
}

void TracePlayer::reset() {
  step_ = 0;
  playing_ = false;
  carry_ = 0.0;
}

void TracePlayer::play() {
  if (events_.empty()) return;
  if (at_end()) step_ = 0;
  playing_ = true;
  carry_ = 0.0;
}

void TracePlayer::set_speed(double steps_per_second) {
  // NaN compares false both ways: treat it as the default.
  if (!(steps_per_second == steps_per_second)) steps_per_second = kDefaultSpeed;
  speed_ = std::clamp(steps_per_second, kMinSpeed, kMaxSpeed);
}

bool TracePlayer::advance(double seconds) {
  if (!playing_ || events_.empty() || !(seconds > 0.0)) return false;
  carry_ += seconds * speed_;
  const double whole = std::floor(carry_);
  carry_ -= whole;
  const size_t before = step_;
  if (whole >= 1.0) step_forward(whole >= double(events_.size()) ? events_.size() : size_t(whole));
  if (at_end()) {
    playing_ = false;
    carry_ = 0.0;
  }
  return step_ != before;
}

bool TracePlayer::step_forward(size_t n) {
  if (events_.empty()) return false;
  const size_t last = events_.size() - 1;
  return seek(n >= last - step_ ? last : step_ + n);
}

bool TracePlayer::step_back(size_t n) { return seek(n >= step_ ? 0 : step_ - n); }

bool TracePlayer::seek(size_t step) {
  const size_t clamped = events_.empty() ? 0 : std::min(step, events_.size() - 1);
  const bool changed = clamped != step_;
  step_ = clamped;
  return changed;
}

bool TracePlayer::jump_to_hit() {
  playing_ = false;
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
