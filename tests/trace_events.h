#pragma once
// Hand-made trace events for the tests of what is derived from a trace (the player's
// highlights, the naive first-leaf answer): a Visit, a Pop, a triangle test and so on in one
// call each.
#include "trace.h"

namespace accel::testing::events {

inline TraceEvent event(TraceEventKind kind, NodeId node = kNoNode, float t0 = 0.0f, float t1 = 0.0f) {
  TraceEvent e;
  e.kind = kind;
  e.node = node;
  e.t0 = t0;
  e.t1 = t1;
  return e;
}
inline TraceEvent test_prim(int32_t prim, bool hit, float t = kInf) {
  TraceEvent e = event(TraceEventKind::TestPrim, kNoNode, hit ? t : kInf, hit ? t : kInf);
  e.prim = prim;
  e.hit = hit;
  return e;
}
inline TraceEvent new_closest(int32_t prim, float t) {
  TraceEvent e = event(TraceEventKind::NewClosest, kNoNode, t, t);
  e.prim = prim;
  e.hit = true;
  return e;
}
inline TraceEvent done(int32_t prim, float t) {
  TraceEvent e = event(TraceEventKind::Done, kNoNode, t, t);
  e.prim = prim;
  e.hit = prim >= 0;
  return e;
}

}  // namespace accel::testing::events
