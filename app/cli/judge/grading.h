#pragma once
// What `accelviz-cli check` and `accelviz-cli grade-class` share: compiling a submission in
// the sandbox, checking every structure of a worker, and the reports (check_command.cpp,
// submission.cpp).
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.h"
#include "judge/remote_student.h"
#include "result.h"
#include "student/grader.h"

namespace cli {

/// Exit code of check and grade-class when the sandbox cannot run here and --no-sandbox
/// was not given: nothing was graded.
inline constexpr int kExitNoSandbox = 3;

/// One structure's report, as check --json writes it (docs/student.md); writes the wrong
/// rays' replay files under `out_dir`/STRUCTURE, whose command starts with `viewer`.
nlohmann::json report_json(const accel::CheckReport& r, const std::string& out_dir, const std::string& viewer,
                           const judge::WorkerBudget& budget);
/// The report of a structure (or a worker) that could not be checked at all.
nlohmann::json failed_report(const std::string& structure, const std::string& failure,
                             const judge::WorkerBudget& budget);
/// The table a person reads.
void print_report(const nlohmann::json& r);

/// Reads --memory-limit, checks --ray-scale, and refuses to grade when the sandbox cannot run
/// and --no-sandbox was not given: 0, or the exit code after one line on stderr.
int prepare_judge_options(CheckOptions& o, const char* command);

/// accelviz-worker beside this program (what `scripts/build.sh --student DIR` builds), "" when
/// this program's path cannot be read.
std::string worker_beside_cli();

/// The worker's limits and confinement from check's options.
std::shared_ptr<judge::WorkerBudget> make_budget(const std::string& worker, const CheckOptions& o);
accel::CheckOptions grader_options(const CheckOptions& o);

/// Lists the worker's structures (in its confinement) and checks each, or only `only`:
/// their reports. An error is bad use (an unknown or built-in name), never the student's
/// fault: a worker that dies or never answers gives a failed report.
accel::Result<nlohmann::json> check_worker(const std::shared_ptr<judge::WorkerBudget>& budget,
                                           const accel::CheckOptions& co, const std::string& only,
                                           const std::string& out_dir, const std::string& viewer);

/// A submission compiled into a worker, in the sandbox.
struct Submission {
  nlohmann::json compile;      ///< {"ok", "seconds", "error"}: the compiler's first error for the student
  std::string worker;          ///< the worker program, when it compiled
  std::string error_for_user;  ///< the submission could not even be tried (no such folder): bad use
};

/// Compiles the .cpp files of `dir` with the kit's header and runtime into a worker under
/// `build_dir`, confined like the worker (no network, a read-only view of a private copy
/// of the submission's files, the kit and /usr), with limits on time and memory.
Submission compile_submission(const std::string& dir, const std::string& build_dir, const CheckOptions& o);

/// A hash of what grading `dir` depends on: its files (names and contents), this grader and
/// its options. Unchanged, a submission's last report stands.
std::string submission_hash(const std::string& dir, const CheckOptions& o);

}  // namespace cli
