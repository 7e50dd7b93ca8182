#pragma once
// One background computation of the viewer (a build, a recording, a heat map, a comparison,
// a sweep): std::async natively; in the web page, which has one thread, a
// browser::BackgroundTask run in slices between frames. Jobs hold what they read (the Scene,
// the Structure) through shared_ptr, so a scene loaded or a structure swapped meanwhile stays
// alive until every job using it has finished.
#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <memory>

#include "browser.h"

namespace viz {

/// One background computation returning T. start() while busy is not allowed (the caller
/// queues instead); the destructor cancels and waits, so no job outlives its owner.
template <class T>
class Job {
 public:
  using Fn = std::function<T(const std::atomic<bool>& cancel)>;
  Job() = default;
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;
  ~Job() { wait(); }

  /// Runs `fn` on a new thread (in the page: as a background task); `synchronous` runs it
  /// here (script mode).
  void start(Fn fn, bool synchronous = false) {
    wait();
    cancel_ = std::make_shared<std::atomic<bool>>(false);
    start_ = std::chrono::steady_clock::now();
    auto flag = cancel_;
    if (synchronous) {
      std::promise<T> p;
      p.set_value(fn(*flag));
      future_ = p.get_future();
    } else if constexpr (browser::kInBrowser) {
      auto promise = std::make_shared<std::promise<T>>();
      future_ = promise->get_future();
      task_ = std::make_unique<browser::BackgroundTask>(
          [fn = std::move(fn), flag, promise] {
            try {
              promise->set_value(fn(*flag));
            } catch (...) {  // as std::async would: take() rethrows it
              promise->set_exception(std::current_exception());
            }
          });
    } else {
      future_ = std::async(std::launch::async, [fn = std::move(fn), flag] { return fn(*flag); });
    }
  }
  /// True while started and not yet taken.
  bool busy() const { return future_.valid(); }
  /// True when the result can be taken without blocking.
  bool ready() const {
    if (task_) return task_->done();
    return future_.valid() && future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  }
  /// The result (blocks until done). The job is idle afterwards.
  T take() {
    task_.reset();  // the page: runs it to the end first
    return future_.get();
  }
  /// Asks the job to stop early (it decides what a cancelled result is).
  void cancel() {
    if (cancel_) cancel_->store(true);
  }
  /// Cancels and waits for the thread, dropping its result.
  void wait() {
    cancel();
    task_.reset();  // the page: runs the cancelled task to its end (its next check)
    if (future_.valid()) future_.wait();
    future_ = {};
  }
  /// Seconds since start().
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::future<T> future_;
  std::unique_ptr<browser::BackgroundTask> task_;  // the page only: where fn runs
  std::shared_ptr<std::atomic<bool>> cancel_;
  std::chrono::steady_clock::time_point start_{};
};

}  // namespace viz
