#include "trace.h"

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

}  // namespace accel
