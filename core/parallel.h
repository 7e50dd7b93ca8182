#pragma once
// The core's parallel loops, in one place: TBB's when the build has it (ACCEL_WITH_TBB,
// the native default), plain serial loops when it has not (the web build, which runs on
// the page's one thread). Builders and queries call accel::par::parallel_for & co. and
// never test for threads themselves.
//
// The serial versions keep TBB's contract as the builders rely on it: a blocked_range is
// handed out in pieces of at most its grain size (cancellation and progress checks happen
// per piece, as with tbb::simple_partitioner), parallel_reduce folds the pieces in order,
// and parallel_invoke runs its functions left to right. Every builder already makes the
// same structure for any thread count (tests/test_*.cpp compare 1 and 4 threads), so the
// serial build is the one-thread build, bit for bit.
// Without threads, par::yield() (yield_point.h) is where long work may pause for the page.
#include <cstddef>

#include "yield_point.h"  // ACCEL_WITH_TBB, par::yield()

#if ACCEL_WITH_TBB
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>
#else
#include <algorithm>
#include <utility>
#endif

namespace accel::par {

#if ACCEL_WITH_TBB

using tbb::blocked_range;
using tbb::enumerable_thread_specific;
using tbb::parallel_for;
using tbb::parallel_invoke;
using tbb::parallel_reduce;
using tbb::simple_partitioner;
using tbb::task_arena;

/// x += v, atomic (relaxed) as loops on other threads may add too; returns the old value.
template <class T>
T fetch_add(T& x, T v) {
  return std::atomic_ref<T>(x).fetch_add(v, std::memory_order_relaxed);
}

#else

/// x += v (one thread: nothing to synchronise); returns the old value.
template <class T>
T fetch_add(T& x, T v) {
  const T old = x;
  x += v;
  return old;
}

/// [begin, end) with a grain size: the serial loops hand out pieces of at most `grain`.
template <class Value>
class blocked_range {
 public:
  blocked_range(Value begin, Value end, size_t grain = 1) : begin_(begin), end_(end), grain_(grain ? grain : 1) {}
  Value begin() const { return begin_; }
  Value end() const { return end_; }
  size_t size() const { return size_t(end_ - begin_); }
  bool empty() const { return !(begin_ < end_); }
  size_t grainsize() const { return grain_; }

 private:
  Value begin_, end_;
  size_t grain_;
};

/// Stands in for TBB's partitioner argument (the serial loop always cuts at the grain).
struct simple_partitioner {};

/// Calls `body` on consecutive pieces of `range`, each at most its grain size.
template <class Value, class Body, class... Partitioner>
void parallel_for(const blocked_range<Value>& range, const Body& body, Partitioner&&...) {
  for (Value lo = range.begin(); lo < range.end();) {
    const Value hi = Value(lo + std::min<size_t>(range.grainsize(), size_t(range.end() - lo)));
    body(blocked_range<Value>(lo, hi, range.grainsize()));
    lo = hi;
  }
}

/// Calls `body(i)` for i = first .. last-1, in order.
template <class Index, class Body>
void parallel_for(Index first, Index last, const Body& body) {
  for (Index i = first; i < last; ++i) body(i);
}

/// Runs the functions one after the other, left to right.
template <class... Fns>
void parallel_invoke(Fns&&... fns) {
  (std::forward<Fns>(fns)(), ...);
}

/// Folds the pieces of `range` in order: value = body(piece, value), starting at identity.
template <class Value, class T, class Body, class Join>
T parallel_reduce(const blocked_range<Value>& range, const T& identity, const Body& body, const Join&) {
  T value = identity;
  parallel_for(range, [&](const blocked_range<Value>& piece) { value = body(piece, value); });
  return value;
}

/// One thread's copy of T; with one thread there is exactly one.
template <class T>
class enumerable_thread_specific {
 public:
  T& local() { return value_; }
  T* begin() { return &value_; }
  T* end() { return &value_ + 1; }

 private:
  T value_{};
};

/// A thread-count limit has nothing to limit: execute() just calls.
class task_arena {
 public:
  static constexpr int automatic = -1;
  explicit task_arena(int = automatic) {}
  template <class Fn>
  auto execute(Fn&& fn) -> decltype(fn()) {
    return fn();
  }
};

#endif

}  // namespace accel::par
