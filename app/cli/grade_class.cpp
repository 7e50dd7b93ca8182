// accelviz-cli grade-class SUBMISSIONS --out DIR: every subfolder of SUBMISSIONS is one
// student's submission. Each is compiled into its own worker and checked in the sandbox
// (judge/grading.h), several at once; an unchanged submission (same files, same grader and
// options: submission_hash) keeps its last report. Writes, in DIR:
//   STUDENT/report.json   the student's report (check --json's, plus compile and hash)
//   STUDENT/replays/      the wrong rays' viewer state files
//   class.csv             one row per student
//   class.html            the class report: table, traps, leaderboard, faults (offline)
//   class.json            everything above, for a course's own tools
// The judge's folder is never visible to the student's code: workers see only their binary.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "class_report.h"
#include "judge/confinement.h"
#include "judge/grading.h"
#include "rays_io.h"

namespace cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

/// The students: the subfolders of `dir`, by name (hidden ones skipped).
std::vector<std::string> student_folders(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_directory(ec) && !e.is_symlink(ec) && e.path().filename().native()[0] != '.')
      out.push_back(e.path().filename().native());
  std::sort(out.begin(), out.end());
  return out;
}

/// A student's folder name as a file name in DIR: the same unless it holds odd characters.
std::string file_safe(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) c = '_';
  return s.empty() || s[0] == '.' ? "_" + s : s;
}

json read_json(const fs::path& p) {
  std::ifstream in(p);
  if (!in) return json();
  try {
    json j;
    in >> j;
    return j;
  } catch (const std::exception&) {
    return json();
  }
}

std::string duration_text(double s) {
  char buf[32];
  if (s < 90) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else std::snprintf(buf, sizeof buf, "%d min %02d s", int(s) / 60, int(s) % 60);
  return buf;
}

/// The progress line: a bar, the count, the last student and the time left, estimated from
/// the seconds per submission so far and the jobs running at once.
class Progress {
 public:
  Progress(size_t total, int jobs) : total_(total), jobs_(jobs), start_(Clock::now()), tty_(isatty(2)) {}
  void done(const std::string& student, const std::string& what, bool skipped) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    if (!skipped) ++graded_;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const double left = graded_ ? elapsed / double(done_) * double(total_ - done_) : 0.0;
    const int width = 24, filled = int(double(width) * double(done_) / double(std::max<size_t>(total_, 1)));
    std::fprintf(stderr, "%s[%s%s] %zu/%zu  %s: %s  %s%s", tty_ ? "\r\033[K" : "", std::string(size_t(filled), '#').c_str(),
                 std::string(size_t(width - filled), '.').c_str(), done_, total_, student.c_str(), what.c_str(),
                 done_ == total_ ? ("done in " + duration_text(elapsed)).c_str()
                                 : ("about " + duration_text(left) + " left").c_str(),
                 tty_ && done_ < total_ ? "" : "\n");
    (void)jobs_;
  }

 private:
  std::mutex mutex_;
  size_t total_, done_ = 0, graded_ = 0;
  int jobs_;
  Clock::time_point start_;
  bool tty_;
};

/// Grades one student: compile, check, report. Its record for the class report.
json grade_student(const std::string& name, const GradeClassOptions& o, const fs::path& out, std::mutex& timing) {
  const fs::path sub = fs::path(o.submissions) / name;
  const std::string safe = file_safe(name);
  const fs::path dir = out / safe;
  const auto start = Clock::now();
  std::error_code ec;
  fs::create_directories(dir, ec);
  CheckOptions co = o.check;
  const std::string hash = submission_hash(sub.native(), co);
  json record = {{"student", name}, {"hash", hash}, {"report", safe + "/report.json"}, {"skipped_unchanged", false}};
  if (!o.force) {
    const json last = read_json(dir / "report.json");
    if (last.is_object() && last.value("hash", "") == hash && last.contains("structures")) {
      json kept = last;
      kept["skipped_unchanged"] = true;
      return kept;
    }
  }
  const Submission compiled = compile_submission(sub.native(), (out / ".build" / safe).native(), co);
  record["compile"] = compiled.compile;
  record["structures"] = json::array();
  if (compiled.compile.value("ok", false)) {
    auto budget = make_budget(compiled.worker, co);
    accel::CheckOptions gco = grader_options(co);
    gco.timing_mutex = &timing;  // one timing at a time: two never share the cores
    auto reports = check_worker(budget, gco, "", (dir / "replays").native(),
                                "scripts/run.sh --student " + sub.native());
    record["structures"] = reports ? reports.value() : json::array({failed_report("(the worker)", reports.error().message, *budget)});
  }
  bool passed = compiled.compile.value("ok", false) && !record["structures"].empty();
  for (const auto& r : record["structures"]) passed = passed && r.value("passed", false);
  record["passed"] = passed;
  record["seconds"] = std::chrono::duration<double>(Clock::now() - start).count();
  accel::write_file_atomic((dir / "report.json").native(), record.dump(1, ' ', false, json::error_handler_t::replace) + "\n");
  return record;
}

std::string now_text() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return buf;
}

}  // namespace

int run_grade_class(const GradeClassOptions& options) {
  GradeClassOptions o = options;
  CheckOptions& co = o.check;
  if (const int bad = prepare_judge_options(co, "grade-class")) return bad;
  std::error_code ec;
  if (!fs::is_directory(o.submissions, ec)) {
    std::fprintf(stderr, "accelviz-cli: grade-class: %s: no such folder\n", o.submissions.c_str());
    return kExitBadInput;
  }
  const fs::path out = fs::absolute(o.out, ec);
  fs::create_directories(out, ec);
  if (ec) {
    std::fprintf(stderr, "accelviz-cli: grade-class: %s: cannot create the folder: %s\n", o.out.c_str(), ec.message().c_str());
    return kExitBadInput;
  }
  // The output folder inside the submissions would be graded as a student, and seen by them.
  const fs::path subs = fs::canonical(o.submissions, ec);
  if (fs::canonical(out, ec).native().rfind(subs.native() + "/", 0) == 0) {
    std::fprintf(stderr, "accelviz-cli: grade-class: --out must not lie inside %s\n", o.submissions.c_str());
    return kExitBadInput;
  }
  const std::vector<std::string> students = student_folders(o.submissions);
  if (students.empty()) {
    std::fprintf(stderr, "accelviz-cli: grade-class: %s: no submission folder in it\n", o.submissions.c_str());
    return kExitBadInput;
  }
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = o.jobs > 0 ? o.jobs : int(cores);
  std::fprintf(stderr, "grading %zu submissions of %s, %d at a time, in %s\n", students.size(), o.submissions.c_str(),
               jobs, out.c_str());
  const auto start = Clock::now();
  std::vector<json> records(students.size());
  std::atomic<size_t> next{0};
  std::mutex timing;
  Progress progress(students.size(), jobs);
  std::vector<std::thread> pool;
  for (int j = 0; j < std::min<int>(jobs, int(students.size())); ++j)
    pool.emplace_back([&] {
      for (size_t i; (i = next++) < students.size();) {
        records[i] = grade_student(students[i], o, out, timing);
        const json& r = records[i];
        const std::string what = !r["compile"].value("ok", false) ? "compile error"
                                 : r.value("passed", false)      ? "passed"
                                                                 : "failed";
        progress.done(students[i], what, r.value("skipped_unchanged", false));
      }
    });
  for (std::thread& t : pool) t.join();
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();

  json cls = {{"title", "accelviz class report"},
              {"generated", now_text()},
              {"submissions_dir", subs.native()},
              {"sandbox", judge::describe_confinement(make_budget("", co)->confinement)},  // every worker's
              {"ray_scale", co.ray_scale},
              {"wall_seconds", wall},
              {"jobs", jobs},
              {"students", records}};
  size_t passed = 0;
  for (const json& r : records) passed += r.value("passed", false);
  const std::string dump = cls.dump(1, ' ', false, json::error_handler_t::replace);
  bool written = accel::write_file_atomic((out / "class.json").native(), dump + "\n").ok() &&
                 accel::write_file_atomic((out / "class.csv").native(), class_report_csv(cls)).ok() &&
                 accel::write_file_atomic((out / "class.html").native(), class_report_html(cls)).ok();
  if (!written) {
    std::fprintf(stderr, "accelviz-cli: grade-class: %s: cannot write the class report\n", out.c_str());
    return kExitBadInput;
  }
  std::printf("%zu of %zu submissions passed; %s wall, %.1f s per submission (%d at a time)\n", passed, records.size(),
              duration_text(wall).c_str(), wall / double(records.size()), jobs);
  std::printf("class report: %s\nCSV: %s\n", (out / "class.html").c_str(), (out / "class.csv").c_str());
  return 0;
}

}  // namespace cli
