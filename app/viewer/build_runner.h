#pragma once
// The viewer's structure builds in the background (BuildRunner): one at a time in a Job, the
// newest request replacing a waiting one and cancelling the running one. GL-free, so
// tests/app/test_build_runner.cpp drives it with a slow fake build.
#include <functional>
#include <memory>
#include <optional>

#include "build_control.h"
#include "built_structure.h"
#include "job.h"
#include "result.h"

namespace viz {

/// The viewer's structure builds: one at a time in a background Job, each with its own
/// BuildControl. A request while a build runs cancels that build and waits as the next one
/// (one deep: a newer request replaces it); it starts as soon as the cancelled job returns,
/// and the cancelled job's result is dropped without a word. GL-free, so it is unit-tested.
class BuildRunner {
 public:
  /// How a build is run (tests pass a slow fake); the default is build_structure_now.
  using BuildFn = std::function<accel::Result<BuiltPtr>(std::shared_ptr<const accel::Scene>, const StructureRequest&,
                                                        accel::BuildControl*)>;
  BuildRunner();
  explicit BuildRunner(BuildFn build);
  BuildRunner(const BuildRunner&) = delete;
  BuildRunner& operator=(const BuildRunner&) = delete;
  /// Cancels the running build and waits for it.
  ~BuildRunner();

  /// Builds `request` over `scene`: now when idle or `synchronous` (script mode: runs on
  /// this thread, the result is ready for the next poll()), else after cancelling the
  /// running build.
  void request(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request, bool synchronous);
  /// The outcome of a finished build that was not cancelled, or nothing; starts the waiting
  /// request when a build has just returned.
  std::optional<accel::Result<BuiltPtr>> poll();
  /// True while a build runs or waits to start.
  bool busy() const { return job_.busy() || next_.has_value(); }
  /// Fraction of the running build done (0 while a cancelled one winds down).
  double fraction() const;
  /// Seconds the running build has taken.
  double seconds() const { return job_.seconds(); }
  /// Cancels the running build, forgets the waiting one, and waits for the thread.
  void wait();
  /// Stops the running build and forgets the waiting one without waiting (the Cancel
  /// button): the thread returns at the builder's next check and poll() drops its result.
  void cancel();
  /// The memory budget of the builds started from now on, in bytes (0: the default,
  /// accel::default_memory_limit()). A build over it fails with an error naming the
  /// parameter to lower, as in the CLI's --memory-limit.
  void set_memory_limit(size_t bytes) { memory_limit_ = bytes; }
  size_t memory_limit() const { return memory_limit_; }

 private:
  struct Pending {
    std::shared_ptr<const accel::Scene> scene;
    StructureRequest request;
  };
  void start(Pending pending, bool synchronous);

  BuildFn build_;
  Job<accel::Result<BuiltPtr>> job_;
  std::shared_ptr<accel::BuildControl> control_;  // of the running build; the job holds it too
  std::optional<Pending> next_;                   // asked for while a build was running
  size_t memory_limit_ = 0;
};

}  // namespace viz
