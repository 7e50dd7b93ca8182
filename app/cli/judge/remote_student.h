#pragma once
// The judge's side of a student's worker process: a proxy student object. The core's
// adapter (KitStructure) and grader treat it as the student's structure; its build() and
// intersect() send the scene and the rays to the worker and replay, onto the kit's own
// logs, the calls the student's code made there. So the judge runs the same checks as the
// viewer runs on linked-in code, and never runs a line of the student's.
//
// One worker process per student object (one per case of a check): a crash ends only that
// process, and a case starts clean.
#include <chrono>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "accelviz_student.h"
#include "judge/confinement.h"
#include "student/kit_registry.h"
#include "student/kit_structure.h"
#include "student/worker_protocol.h"

namespace judge {

/// What the worker processes of one structure's check may use, shared by them all, and what
/// they printed.
struct WorkerBudget {
  std::string worker;  ///< the worker program (a full path)
  Confinement confinement;
  double timeout_seconds = 0.0;  ///< wall seconds for one check (0: none)
  size_t output_limit = size_t(8) << 20;

  /// Starts a check's clock and forgets the last one's output.
  void start_check();
  /// A new wall-clock allowance, the output kept (the timing after the correctness check).
  void restart_deadline();
  /// Past the check's time limit.
  std::chrono::steady_clock::time_point deadline() const;
  /// What the student's code printed (the first kOutputKept bytes) and how much in all.
  std::string output() const;
  size_t output_bytes() const;
  /// Keeps `data` printed by a worker; false once the check's output is past the limit.
  bool take_output(const char* data, size_t size);

  static constexpr size_t kOutputKept = 2048;

 private:
  mutable std::mutex mutex_;
  std::chrono::steady_clock::time_point deadline_ = std::chrono::steady_clock::time_point::max();
  std::string output_;
  size_t output_bytes_ = 0;
};

/// A running worker: frames both ways, its output drained as it comes, the deadline and the
/// output limit kept. Every way it can stop answering is a StudentProcessLost.
class WorkerChannel {
 public:
  explicit WorkerChannel(std::shared_ptr<WorkerBudget> budget);  ///< starts it (or throws)
  ~WorkerChannel();  ///< ends it
  WorkerChannel(const WorkerChannel&) = delete;
  WorkerChannel& operator=(const WorkerChannel&) = delete;

  void send(accel::wire::Msg type, const std::string& payload);
  accel::wire::Msg receive(std::string& payload);

 private:
  /// Waits until the answers or the output move, or the deadline; reads what came.
  void pump(bool for_writing);
  [[noreturn]] void lost(const std::string& what, const std::string& hint);
  [[noreturn]] void ended();
  void stop();

  std::shared_ptr<WorkerBudget> budget_;
  Confined process_;
  bool reaped_ = false;
  int status_ = 0;
  std::string in_;  ///< answers read, not yet taken
  size_t in_at_ = 0;
  bool answers_closed_ = false;
};

/// The structures the worker holds, asked of it in its confinement (their registrations run
/// the student's static initialisers: never in the judge).
accel::Result<std::vector<accel::StudentRegistration>> list_worker(const std::shared_ptr<WorkerBudget>& budget);

/// Registry entries whose student objects are RemoteStudents of `budget`'s worker.
std::vector<accel::StudentEntry> remote_entries(const std::vector<accel::StudentRegistration>& registrations,
                                                const std::shared_ptr<WorkerBudget>& budget);

/// A student object whose code runs in a worker process.
class RemoteStudent final : public accelviz::StudentStructure, public accel::RemoteAnswers {
 public:
  RemoteStudent(std::string name, std::shared_ptr<WorkerBudget> budget);

  void build(const accelviz::Scene& scene, accelviz::BuildLog& log) override;
  accelviz::Hit intersect(const accelviz::Ray& ray, accelviz::TraversalLog log) const override;
  void expect(const std::vector<accel::Ray>& rays, accel::Kernel kernel, uint8_t modes) override;
  double time_rays(const std::vector<accel::Ray>& rays, accel::Kernel kernel, unsigned threads,
                   std::vector<accel::Hit>* answers) override;

 private:
  struct Pending {
    accel::wire::WireRay ray;
    uint8_t mode;
  };
  /// Reads one ray's answer, replaying its traversal frames onto `log` (if it listens).
  accelviz::Hit take_answer(accelviz::TraversalLog log) const;
  /// Reads and drops the answers still owed for rays the grader did not ask after all.
  void drop_pending() const;
  /// Reads and drops the next answer owed.
  void skip_pending() const;
  /// After `traced` threw: the fast answer of the same ray is not owed.
  void drop_fast_after_throw(const Pending& traced) const;
  WorkerChannel& channel() const;

  std::string name_;
  std::shared_ptr<WorkerBudget> budget_;
  mutable std::mutex mutex_;  // intersect() may be called from several threads: one at a time
  mutable std::unique_ptr<WorkerChannel> channel_;
  mutable std::deque<Pending> pending_;
};

}  // namespace judge
