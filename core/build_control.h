#pragma once
// BuildControl: the channel between a running build and whoever started it -- progress out
// (a fraction in [0, 1]), cancellation in. The viewer builds on a background thread and
// reads the fraction from its UI thread, so both sides are atomics. Builders poll
// cancelled() at coarse points (per node, per batch of triangles, between phases) and then
// return cancelled_error(); the CLI, the bench and the tests may pass no control at all.
// The control also carries the build's limits: the memory budget every builder checks its
// allocations against (memory_budget.h) and a time limit, which turns a build that would
// run for minutes into an error in the CLI (the viewer shows progress and Cancel instead).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <thread>
#include <utility>

#include "memory_budget.h"
#include "result.h"
#include "yield_point.h"

namespace accel {

/// Progress and cancellation of one build. Not copyable (the build holds a pointer to it);
/// one control per build.
class BuildControl {
 public:
  /// Called on the build thread with every reported fraction (tests record them).
  using ProgressFn = std::function<void(double fraction)>;

  BuildControl() = default;
  /// A control that also calls `on_progress` after every report().
  explicit BuildControl(ProgressFn on_progress) : on_progress_(std::move(on_progress)) {}
  BuildControl(const BuildControl&) = delete;
  BuildControl& operator=(const BuildControl&) = delete;

  /// Asks the build to stop at its next check (any thread, any number of times).
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  /// Also stops the build once `*flag` is true: a flag the caller owns and outlives the
  /// build (the CLI's SIGINT flag). nullptr: none.
  void set_cancel_flag(const std::atomic<bool>* flag) { cancel_flag_ = flag; }

  /// True once cancel() was called, the cancel flag was set or the time limit passed. Cheap
  /// (relaxed loads, and a clock read only with a time limit): builders may poll it per node.
  bool cancelled() const {
    par::yield();  // without threads: the page's other work runs here between slices
    if (cancelled_.load(std::memory_order_relaxed)) return true;
    if (cancel_flag_ && cancel_flag_->load(std::memory_order_relaxed)) return true;
    if (deadline_ == Clock::time_point::max() || Clock::now() < deadline_) return false;
    timed_out_.store(true, std::memory_order_relaxed);
    return true;
  }

  /// The memory budget of the build in bytes (set before the build starts); 0 = the
  /// default, default_memory_limit().
  void set_memory_limit(size_t bytes) { memory_limit_ = bytes; }
  size_t memory_limit() const { return memory_limit_ ? memory_limit_ : default_memory_limit(); }

  /// Stops the build, as cancel() does, once `seconds` have passed from now (<= 0: none).
  void set_time_limit(double seconds) {
    time_limit_ = seconds;
    deadline_ = seconds > 0.0 ? Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                   std::chrono::duration<double>(seconds))
                              : Clock::time_point::max();
  }
  double time_limit() const { return time_limit_; }
  /// True when the build stopped because the time limit passed (not by cancel()).
  bool timed_out() const { return timed_out_.load(std::memory_order_relaxed); }

  /// Stores the fraction of the build done, clamped to [0, 1] (build thread). Builders
  /// report a non-decreasing sequence ending at 1.0 on success; the control does not
  /// enforce it, so the tests can check the builders do.
  void report(double fraction) {
    fraction = std::clamp(fraction, 0.0, 1.0);
    fraction_.store(fraction, std::memory_order_relaxed);
    if (on_progress_) on_progress_(fraction);
  }
  /// The last reported fraction (0 before the first report; any thread).
  double fraction() const { return fraction_.load(std::memory_order_relaxed); }

 private:
  using Clock = std::chrono::steady_clock;
  std::atomic<bool> cancelled_{false};
  const std::atomic<bool>* cancel_flag_ = nullptr;
  mutable std::atomic<bool> timed_out_{false};
  std::atomic<double> fraction_{0.0};
  size_t memory_limit_ = 0;
  double time_limit_ = 0.0;
  Clock::time_point deadline_ = Clock::time_point::max();
  ProgressFn on_progress_;
};

/// The error every cancelled build returns (front ends recognise it by the control, not
/// the text).
inline Error cancelled_error() { return make_error("build cancelled"); }

/// Null-safe helpers: a build without a control neither reports nor stops, and has the
/// default memory budget.
inline bool build_cancelled(const BuildControl* control) { return control && control->cancelled(); }
inline size_t build_memory_limit(const BuildControl* control) {
  return control ? control->memory_limit() : default_memory_limit();
}
/// Reports `fraction` when there is a control.
inline void report_progress(BuildControl* control, double fraction) {
  if (control) control->report(fraction);
}

/// Reports a builder's local progress (0..1, e.g. triangles done / N) mapped into the part
/// [lo, hi] of the whole build, and only when it moved by at least 1/1024 of the whole:
/// builders may call advance() per node or per triangle batch without flooding the callback
/// or the atomic. A null control makes it free apart from the null test.
class ProgressSpan {
 public:
  ProgressSpan(BuildControl* control, double lo, double hi) : control_(control), lo_(lo), hi_(hi), last_(lo) {}

  /// Local progress `local` in [0, 1]; returns false when the build was cancelled.
  bool advance(double local) {
    if (!control_) return true;
    const double f = lo_ + (hi_ - lo_) * std::clamp(local, 0.0, 1.0);
    if (f >= last_ + kStep) {
      last_ = f;
      control_->report(f);
    }
    return !control_->cancelled();
  }
  /// Reports the end of the span (local progress 1) exactly.
  void finish() {
    if (control_ && last_ < hi_) {
      last_ = hi_;
      control_->report(hi_);
    }
  }
  /// Whether the build was cancelled.
  bool cancelled() const { return build_cancelled(control_); }
  /// Whether there is a control to report to (without one, advance() does nothing).
  bool reports() const { return control_ != nullptr; }
  /// The last fraction reported through this span (lo before any report).
  double last() const { return last_; }

 private:
  static constexpr double kStep = 1.0 / 1024.0;
  BuildControl* control_;
  double lo_, hi_, last_;
};

/// The progress of a build whose tasks run on many threads: each task adds the work it
/// finished (triangles placed in leaves, a batch of cells, a leaf's share of the build) from
/// any thread, lock-free; the thread that made the counter reports the running total through
/// its ProgressSpan (which is single-threaded); every task asks stopped() before it starts.
/// Every parallel builder counts through one of these.
class ProgressCounter {
 public:
  /// The total of a counter of shares (a leaf's share of the build, its parent's share
  /// split among the children): add_share(s) adds s of the whole, in fixed point, rounded
  /// down so the sum of the shares never passes 1.
  static constexpr uint64_t kWhole = uint64_t(1) << 52;

  /// A counter of `total` units reporting done / total to `span`. Without a span, or a span
  /// without a control, it counts nothing (no shared atomic in the fast path) and never stops.
  ProgressCounter(ProgressSpan* span, uint64_t total)
      : span_(span && span->reports() ? span : nullptr), total_(double(total)) {}
  ProgressCounter(const ProgressCounter&) = delete;
  ProgressCounter& operator=(const ProgressCounter&) = delete;

  /// Adds `units` of finished work (any thread); on the counter's thread, reports the total.
  /// Cancellation is stopped()'s to see (builders check it per node or batch).
  void add(uint64_t units) {
    if (!span_) return;
    // One access to the shared line per call: builders add per leaf, from every thread.
    const uint64_t done = done_.fetch_add(units, std::memory_order_relaxed) + units;
    if (std::this_thread::get_id() != owner_ || stop_.load(std::memory_order_relaxed)) return;
    if (!span_->advance(std::min(1.0, double(done) / total_))) stop_.store(true, std::memory_order_relaxed);
  }
  /// add() of `share` (in [0, 1]) of a kWhole counter.
  void add_share(double share) { add(uint64_t(share * double(kWhole))); }

  /// True once the build was cancelled (any thread): tasks check it before they start.
  bool stopped() const { return span_ && (stop_.load(std::memory_order_relaxed) || span_->cancelled()); }

 private:
  ProgressSpan* span_;
  double total_;
  std::thread::id owner_ = std::this_thread::get_id();
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> done_{0};
};

}  // namespace accel
