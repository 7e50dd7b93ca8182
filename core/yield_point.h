#pragma once
// par::yield(): where long work may pause for the rest of the page. Without threads (the web
// build, ACCEL_WITH_TBB=0) a build or a batch of rays holds the page's one thread; the web
// viewer runs such work as a background task and sets the hook, which hands the thread back
// once the task's slice of the frame is used. Builders reach it through BuildControl's
// checks (build_control.h), batch queries every 64 rays. With threads it is empty.
#ifndef ACCEL_WITH_TBB
#define ACCEL_WITH_TBB 1
#endif

namespace accel::par {

#if ACCEL_WITH_TBB

inline void yield() {}

#else

/// What yield() calls; null: nothing (work started outside a background task).
using YieldHook = void (*)();
inline YieldHook& yield_hook() {
  static YieldHook hook = nullptr;
  return hook;
}
inline void yield() {
  if (YieldHook hook = yield_hook()) hook();
}

#endif

}  // namespace accel::par
