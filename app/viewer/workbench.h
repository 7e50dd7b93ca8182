#pragma once
// The viewer's work that needs no window: building a structure (on a background thread),
// the debug ray and its recorded trace, the "same ray, every structure" comparison and the
// parameter sweep. App drives these and draws their results; the tests call them directly.
//
// Threads: a build, a heat map, a comparison or a sweep runs in a Job (std::async; in the
// web page, which has one thread, a browser::BackgroundTask run in slices between frames). Jobs
// hold the Scene and the Structure through shared_ptr, so a scene loaded or a structure
// swapped meanwhile stays alive until every job using it has finished. Structures are
// const once built: queries from any thread are safe.
#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "browser.h"
#include "build_control.h"
#include "pseudo_code.h"
#include "registry.h"
#include "ray_gen.h"
#include "structure.h"
#include "structure_view.h"
#include "trace_player.h"

namespace viz {

// ---------------------------------------------------------------------------------------
// Background jobs

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

// ---------------------------------------------------------------------------------------
// Structures

/// What to build: names and parameters exactly as accelviz-cli takes them.
struct StructureRequest {
  std::string name = "bvh";
  std::vector<std::string> params;  ///< key=value
  accel::Kernel kernel = accel::Kernel::Watertight;
  GeometryOptions geometry;
};

/// A built structure with everything the viewer shows about it, made on the build thread.
struct BuiltStructure {
  std::shared_ptr<const accel::Scene> scene;  ///< kept alive as long as the structure
  std::unique_ptr<accel::Structure> structure;
  const accel::StructureInfo* info = nullptr;  ///< its registry entry (label, node noun, ...)
  StructureRequest request;
  std::string params_text;      ///< every parameter, "key=value ..."
  accel::BuildStats stats;
  StructureGeometry geometry;   ///< instances for drawing
  std::string traversal;        ///< value of its "traversal" parameter ("" when it has none)
  TraversalKind kind = TraversalKind::Unknown;
};
using BuiltPtr = std::shared_ptr<const BuiltStructure>;

/// Validates, builds and lists the nodes of a structure over `scene` (any thread).
/// Errors name the structure or parameter (from the registry). `control` (optional) gets
/// the build's progress and can cancel it (then the error is accel::cancelled_error()).
accel::Result<BuiltPtr> build_structure_now(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                                            accel::BuildControl* control = nullptr);

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

/// Replaces `key`'s value in a key=value list (appends it when absent).
std::vector<std::string> with_param(std::vector<std::string> params, const std::string& key, const std::string& value);
/// The value of `key` in a key=value list, or `fallback`.
std::string param_value(const std::vector<std::string>& params, const std::string& key, const std::string& fallback = "");

// ---------------------------------------------------------------------------------------
// The debug ray

/// The ray being debugged and its recorded traversal.
struct DebugRay {
  bool active = false;
  accel::Ray ray;
  std::string origin;          ///< how it was made: "click", "typed", "preset", "script"
  accel::Hit hit;              ///< intersect_traced's answer
  accel::QueryStats stats;     ///< counters of the whole trace
  accel::TracePlayer player;
  /// The loop's variables recorded with the trace (grid, kd-tree, octree); see vars_at().
  std::vector<accel::RecordedVars> vars;
  /// The traversal made more steps than the recorder's budget keeps: the player has the
  /// first ones and the answer; `stats` count the whole traversal all the same.
  bool truncated = false;

  /// Records the ray's traversal of `s` (its real intersect_traced). keep_step: the same ray
  /// replayed after a rebuild keeps its step, clamped.
  void record(const accel::Structure& s, bool keep_step);
};

/// The ray's end point for drawing: the hit, or where it leaves `bounds` (grown a little),
/// or a fallback length when it misses the scene box entirely.
float ray_draw_length(const accel::Ray& ray, const accel::Hit& hit, const accel::Aabb& bounds);

// ---------------------------------------------------------------------------------------
// Same ray, every structure and traversal

struct CompareRow {
  std::string label;                 ///< "bvh (pqueue)"
  std::string structure;
  std::vector<std::string> params;   ///< as built
  bool current = false;              ///< the structure and traversal shown now
  bool ok = false;
  std::string error;
  accel::QueryStats stats;           ///< intersect(ray, &stats)
  size_t steps = 0;                  ///< events recorded by intersect_traced
  accel::Hit hit;
  double build_ms = 0.0;
};

/// One row per built-in structure of the registry (and the current one when it is a
/// student's), and per value of its "traversal" parameter when
/// it has one. The current structure keeps its parameters (the traversal varied); others
/// use their defaults. Each row is a real build + intersect(ray, &stats) + a traced query.
/// Stops early when cancelled; `progress` counts finished rows.
std::vector<CompareRow> compare_structures(std::shared_ptr<const accel::Scene> scene, const accel::Ray& ray,
                                           const StructureRequest& current, const std::atomic<bool>& cancel,
                                           std::atomic<int>* progress = nullptr);

// ---------------------------------------------------------------------------------------
// Parameter sweep ("tune at the end")

struct SweepRequest {
  StructureRequest base;          ///< structure and its other parameters
  std::string param;              ///< an Int or Float parameter of base.name
  double lo = 0.0, hi = 1.0;
  int steps = 10;
  bool log_scale = false;         ///< geometric spacing (for wide ranges)
  accel::PinholeCamera camera;    ///< the fixed ray set: primary rays of this camera
  int width = 128, height = 96;
};

struct SweepPoint {
  double value = 0.0;
  std::string text;               ///< the value as passed to the structure
  bool ok = false;
  std::string error;
  double build_ms = 0.0;
  double trace_ms = 0.0;          ///< the whole ray set, all threads, best of 3
  double nodes_per_ray = 0.0;
  double prims_per_ray = 0.0;
  size_t nodes = 0;
  double sah_cost = 0.0;
};

/// Points filled in by run_sweep() as it goes, read by the UI meanwhile.
struct SweepProgress {
  std::mutex mutex;
  std::vector<SweepPoint> points;
  int total = 0;
};

/// The values a sweep tries: `steps` values from lo to hi (geometric when log_scale and
/// lo > 0), Int parameters rounded with duplicates dropped, all clamped to the spec's range.
std::vector<double> sweep_values(const accel::ParamSpec& spec, double lo, double hi, int steps, bool log_scale);

/// Builds and traces once per value; appends each point to `progress` as it finishes.
/// Error when the parameter does not exist or is not numeric.
accel::Status run_sweep(std::shared_ptr<const accel::Scene> scene, const SweepRequest& request,
                              SweepProgress& progress, const std::atomic<bool>& cancel);

}  // namespace viz
