#include "trace.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace accel {

const char* event_kind_name(TraceEventKind kind) {
  switch (kind) {
    case TraceEventKind::Visit: return "visit";
    case TraceEventKind::EnterCell: return "enter-cell";
    case TraceEventKind::Cull: return "cull";
    case TraceEventKind::Push: return "push";
    case TraceEventKind::Pop: return "pop";
    case TraceEventKind::TestPrim: return "test";
    case TraceEventKind::NewClosest: return "closest";
    case TraceEventKind::Done: return "done";
  }
  return "?";
}

const char* cull_reason_name(CullReason reason) {
  switch (reason) {
    case CullReason::None: return "none";
    case CullReason::MissedBounds: return "ray misses its bounds";
    case CullReason::BeyondClosestHit: return "entry beyond the closest hit";
  }
  return "?";
}

std::string describe_event(const TraceEvent& e) {
  char buf[192];
  switch (e.kind) {
    case TraceEventKind::Visit:
      std::snprintf(buf, sizeof buf, "visit node %u (depth %d) t=[%g, %g]", e.node, e.depth, double(e.t0), double(e.t1));
      break;
    case TraceEventKind::EnterCell:
      std::snprintf(buf, sizeof buf, "enter cell %u t=[%g, %g]", e.node, double(e.t0), double(e.t1));
      break;
    case TraceEventKind::Cull:
      std::snprintf(buf, sizeof buf, "skip node %u (depth %d): %s", e.node, e.depth, cull_reason_name(e.reason));
      break;
    case TraceEventKind::Push:
      std::snprintf(buf, sizeof buf, "push node %u (depth %d) key t=%g", e.node, e.depth, double(e.t0));
      break;
    case TraceEventKind::Pop:
      std::snprintf(buf, sizeof buf, "pop node %u (depth %d) key t=%g", e.node, e.depth, double(e.t0));
      break;
    case TraceEventKind::TestPrim:
      if (e.hit) std::snprintf(buf, sizeof buf, "test triangle %d: hit at t=%g", e.prim, double(e.t0));
      else std::snprintf(buf, sizeof buf, "test triangle %d: miss", e.prim);
      break;
    case TraceEventKind::NewClosest:
      std::snprintf(buf, sizeof buf, "new closest hit: triangle %d at t=%g", e.prim, double(e.t0));
      break;
    case TraceEventKind::Done:
      if (e.hit) std::snprintf(buf, sizeof buf, "done: hit triangle %d at t=%g", e.prim, double(e.t0));
      else std::snprintf(buf, sizeof buf, "done: miss");
      break;
  }
  return buf;
}

QueryStats TraceRecorder::stats() const {
  StatsSink sink;
  for (const TraceEvent& e : events_) {
    switch (e.kind) {
      case TraceEventKind::Visit: sink.visit(e.node, e.depth, e.t0, e.t1); break;
      case TraceEventKind::EnterCell: sink.enter_cell(e.node, e.t0, e.t1); break;
      case TraceEventKind::Cull: sink.cull(e.node, e.depth, e.reason, e.t0); break;
      case TraceEventKind::Push: sink.push(e.node, e.depth, e.t0); break;
      case TraceEventKind::Pop: sink.pop(e.node, e.depth, e.t0); break;
      case TraceEventKind::TestPrim: sink.test_prim(uint32_t(e.prim), e.hit, e.t0); break;
      case TraceEventKind::NewClosest: sink.new_closest(uint32_t(e.prim), e.t0); break;
      case TraceEventKind::Done: break;
    }
  }
  return sink.stats;
}

StepListener::~StepListener() = default;

void RecordingListener::visit(NodeId n, int depth, float t0, float t1) { r_.visit(n, depth, t0, t1); }
void RecordingListener::enter_cell(NodeId n, float t0, float t1) { r_.enter_cell(n, t0, t1); }
void RecordingListener::cull(NodeId n, int depth, CullReason why, float t0) { r_.cull(n, depth, why, t0); }
void RecordingListener::push(NodeId n, int depth, float key) { r_.push(n, depth, key); }
void RecordingListener::pop(NodeId n, int depth, float key) { r_.pop(n, depth, key); }
void RecordingListener::test_prim(uint32_t prim, bool hit, float t) { r_.test_prim(prim, hit, t); }
void RecordingListener::new_closest(uint32_t prim, float t) { r_.new_closest(prim, t); }
void RecordingListener::done(const Hit& h) { r_.done(h); }
void RecordingListener::vars(const StepVars& v) { r_.vars(v); }

// ---------------------------------------------------------------------------------------
// The traversal's variables

const char* kd_case_name(KdCase c) {
  switch (c) {
    case KdCase::Both: return "a(both)";
    case KdCase::NearOnly: return "b(near_only)";
    case KdCase::FarOnly: return "c(far_only)";
  }
  return "?";
}

namespace {

constexpr const char* kAxisName[3] = {"x", "y", "z"};
constexpr const char* kAxisUpper[3] = {"X", "Y", "Z"};

const char* fate_name(OctreeOrderVars::Fate f) {
  switch (f) {
    case OctreeOrderVars::Fate::Pushed: return "pushed";
    case OctreeOrderVars::Fate::Missed: return "missed";
    case OctreeOrderVars::Fate::BeyondClosestHit: return "beyond_hit";
    case OctreeOrderVars::Fate::Empty: return "empty";
  }
  return "?";
}

// Appends " name=value" with %g (inf prints as inf).
void add(std::string& out, const char* name, double value) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s%s=%g", out.empty() ? "" : " ", name, value);
  out += buf;
}
void add(std::string& out, const std::string& name, const std::string& value) {
  if (!out.empty()) out += ' ';
  out += name + "=" + value;
}

std::string describe(const GridDdaVars& v) {
  std::string s;
  const int dims = v.dims == 2 ? 2 : 3;
  for (int a = 0; a < dims; ++a) add(s, kAxisUpper[a], v.cell[a]);
  for (int a = 0; a < dims; ++a) add(s, (std::string("step") + kAxisUpper[a]).c_str(), v.step[a]);
  for (int a = 0; a < dims; ++a) add(s, (std::string("tMax") + kAxisUpper[a]).c_str(), v.t_max[a]);
  for (int a = 0; a < dims; ++a) add(s, (std::string("tDelta") + kAxisUpper[a]).c_str(), v.t_delta[a]);
  add(s, "next", kAxisName[(v.next_axis % 3 + 3) % 3]);
  return s;
}

std::string describe(const KdSplitVars& v) {
  std::string s;
  add(s, "t_min", v.t_min);
  add(s, "t_split", v.t_split);
  add(s, "t_max", v.t_max);
  add(s, "axis", kAxisName[(v.axis % 3 + 3) % 3]);
  add(s, "near", v.near_child);
  add(s, "far", v.far_child);
  add(s, "case", kd_case_name(v.kase));
  return s;
}

std::string describe(const KdExitVars& v) {
  std::string s;
  add(s, "t_hit", v.t_hit);
  add(s, "t_split", v.t_split);
  add(s, "far", v.far_child);
  add(s, "early_exit", v.exits ? "yes(t_hit<t_split)" : "no");
  return s;
}

std::string describe(const OctreeOrderVars& v) {
  std::string s;
  add(s, "mask", v.mask);
  std::string order;
  for (int i = 0; i < v.count && i < 8; ++i) {
    const OctreeOrderVars::Child& c = v.children[i];
    char buf[96];
    if (c.fate == OctreeOrderVars::Fate::Pushed || c.fate == OctreeOrderVars::Fate::BeyondClosestHit)
      std::snprintf(buf, sizeof buf, "%s%u:%g:%s", order.empty() ? "" : ",", c.node, double(c.t_enter),
                    fate_name(c.fate));
    else
      std::snprintf(buf, sizeof buf, "%s%u:%s", order.empty() ? "" : ",", c.node, fate_name(c.fate));
    order += buf;
  }
  add(s, "order", order.empty() ? "-" : order);
  return s;
}

}  // namespace

std::string describe_vars(const StepVars& vars) {
  return std::visit([](const auto& v) { return describe(v); }, vars);
}

const StepVars* vars_at(std::span<const TraceEvent> events, std::span<const RecordedVars> vars, size_t step) {
  if (events.empty()) return nullptr;
  step = std::min(step, events.size() - 1);
  size_t node_step = 0;  // the last Visit / EnterCell at or before the step
  for (size_t i = step + 1; i-- > 0;) {
    if (events[i].kind == TraceEventKind::Visit || events[i].kind == TraceEventKind::EnterCell) {
      node_step = i;
      break;
    }
  }
  const StepVars* found = nullptr;
  for (const RecordedVars& r : vars) {
    if (r.event > step) break;
    if (r.event >= node_step) found = &r.vars;
  }
  return found;
}

}  // namespace accel
