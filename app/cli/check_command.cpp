// accelviz-cli check: the assignment kit's grader (docs/student.md). The parent process runs
// each student structure's check in a child process of this same binary (`--worker-*`), so
// a crash, an endless loop or a runaway allocation in the student's code is reported with
// the case and the ray it happened on, and never takes the grader down. The child writes
// its report as JSON; the parent prints the table (or --json) and sets the exit code.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "commands.h"
#include "memory_budget.h"
#include "rays_io.h"
#include "registry.h"
#include "student/grader.h"

extern char** environ;

namespace cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// Where the child is, in memory the parent maps too: written at each case and each ray.
struct SharedProgress {
  char where[240];
  volatile uint64_t ray;
};

const char* kVerdictKeys[5] = {"correct", "false_miss", "false_hit", "wrong_triangle", "wrong_t"};

std::string fmt(double v, const char* f = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string safe_name(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '_';
  return s;
}

/// The viewer next to this binary, as a command a person types from the current folder.
std::string viewer_command() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  // accelviz-cli -> accelviz; the kit tests' accelviz-cli-kit -> accelviz-kit.
  std::string name = ec ? std::string("accelviz-cli") : exe.filename().native();
  if (const size_t at = name.find("-cli"); at != std::string::npos) name.erase(at, 4);
  fs::path viewer = ec ? fs::path(name) : exe.parent_path() / name;
  const fs::path rel = fs::relative(viewer, fs::current_path(), ec);
  if (!ec && !rel.empty() && rel.native().rfind("..", 0) != 0) viewer = rel;
  return viewer.native();
}

/// Writes the replay of one wrong ray: a viewer state file (a script of the commands that
/// rebuild the state: scene, structure, ray) and, for generated scenes, their OBJ.
std::string write_replay(const accel::WrongRay& w, const std::string& structure, const std::string& dir, size_t k,
                         std::string* error) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    *error = dir + ": cannot create the folder: " + ec.message();
    return "";
  }
  std::string scene;
  if (w.category == "procedural") {
    scene = "procedural:" + w.case_name;
  } else if (w.scene->triangle_count() == 0) {
    return "";  // an empty scene has no file to open
  } else {
    scene = fs::absolute(fs::path(dir) / (safe_name(w.category + "_" + w.case_name) + ".obj")).native();
    if (!fs::exists(scene)) {
      if (auto s = accel::write_scene_obj(*w.scene, scene); !s) {
        *error = s.error().message;
        return "";
      }
    }
  }
  const std::string state = (fs::path(dir) / ("wrong" + std::to_string(k) + ".state")).native();
  const std::string text = "# accelviz-cli check: " + structure + ", " + w.category + "/" + w.case_name + " ray " +
                           std::to_string(w.index) + ": " + kVerdictKeys[int(w.verdict)] + "\n" + "scene " + scene +
                           "\nstructure " + structure + "\nray " + accel::format_ray_line(w.ray) + "\n";
  if (auto s = accel::write_file_atomic(state, text); !s) {
    *error = s.error().message;
    return "";
  }
  return state;
}

json report_json(const accel::CheckReport& r, const CheckOptions& o) {
  json j;
  j["structure"] = r.structure;
  j["kind"] = r.kind;
  j["builtin"] = r.peer;
  j["source"] = r.source_file;
  j["rays"] = r.rays();
  j["wrong"] = r.wrong();
  j["categories"] = json::array();
  for (const auto& c : r.categories) {
    json wrong;
    for (int v = 1; v < 5; ++v) wrong[kVerdictKeys[v]] = c.wrong[v];
    j["categories"].push_back({{"name", c.name}, {"cases", c.cases}, {"rays", c.rays}, {"wrong", wrong}});
  }
  j["wrong_rays"] = json::array();
  const std::string dir = (fs::path(o.out_dir) / r.structure).native();
  for (size_t k = 0; k < r.wrong_rays.size(); ++k) {
    const accel::WrongRay& w = r.wrong_rays[k];
    std::string error;
    const std::string state = write_replay(w, r.structure, dir, k + 1, &error);
    json jw = {{"category", w.category},
               {"case", w.case_name},
               {"ray", w.index},
               {"verdict", kVerdictKeys[int(w.verdict)]},
               {"got", {{"prim", w.got.prim}, {"t", w.got.valid() ? double(w.got.t) : -1.0}}},
               {"reference", {{"prim", w.ref.prim}, {"t", w.ref.prim >= 0 ? w.ref.t : -1.0}}},
               {"trap", w.trap}};
    if (!state.empty()) {
      jw["state_file"] = state;
      jw["replay"] = viewer_command() + " --restore " + state;
    } else if (!error.empty()) {
      jw["replay_error"] = error;
    }
    j["wrong_rays"].push_back(jw);
  }
  j["invariants"] = json::array();
  for (const auto& i : r.invariants)
    j["invariants"].push_back({{"name", i.name},
                               {"applies", i.applies},
                               {"checked", i.checked},
                               {"failed", i.failed},
                               {"first_failure", i.first_failure}});
  const auto& s = r.speed;
  j["speed"] = {{"timed", s.timed}, {"why_not", s.why_not}, {"workload", s.workload}};
  if (s.timed) {
    j["speed"]["mrays_per_s"] = s.mrays;
    j["speed"]["builtin_mrays_per_s"] = s.peer_mrays;
    j["speed"]["nodes_per_ray"] = s.nodes;
    j["speed"]["builtin_nodes_per_ray"] = s.peer_nodes;
    j["speed"]["triangles_per_ray"] = s.tris;
    j["speed"]["builtin_triangles_per_ray"] = s.peer_tris;
  }
  j["faults"] = r.faults;
  j["failure"] = "";
  j["passed"] = r.passed();
  return j;
}

/// The child: checks one structure, writes the JSON report.
int run_worker(const CheckOptions& o) {
  // The grader that started this child may be stopped (a course's time limit, Ctrl-C): then
  // this child goes too, instead of looping on in the background.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  auto info = accel::find_structure(o.structure);
  if (!info) {
    std::fprintf(stderr, "accelviz-cli: check: %s\n", info.error().message.c_str());
    return kExitBadInput;
  }
  SharedProgress* progress = nullptr;
  if (!o.worker_progress.empty()) {
    const int fd = ::open(o.worker_progress.c_str(), O_RDWR);
    if (fd >= 0) {
      void* p = ::mmap(nullptr, sizeof(SharedProgress), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
      if (p != MAP_FAILED) progress = static_cast<SharedProgress*>(p);
      ::close(fd);
    }
  }
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ACCEL_CHECK_UNDER_ASAN 1
#endif
#endif
#if !defined(__SANITIZE_ADDRESS__) && !defined(ACCEL_CHECK_UNDER_ASAN)
  // ASan reserves terabytes of address space: no limit under it (the sanitizer build).
  if (o.memory_bytes > 0) {  // a runaway allocation ends in std::bad_alloc, reported as a fault
    rlimit lim{rlim_t(o.memory_bytes), rlim_t(o.memory_bytes)};
    setrlimit(RLIMIT_AS, &lim);
  }
#endif
  // The replays of an earlier check of this structure would be mistaken for this one's.
  std::error_code ec;
  fs::remove_all(fs::path(o.out_dir) / o.structure, ec);
  accel::CheckOptions co;
  co.shared_scenes = o.shared;
  co.ray_scale = o.ray_scale;
  co.time = o.time;
  std::string last;
  auto report = accel::check_structure(*info.value(), co, [&](const std::string& where, size_t ray) {
    if (!progress) return;
    if (where != last) {
      last = where;
      std::snprintf(progress->where, sizeof progress->where, "%s", where.c_str());
    }
    progress->ray = ray;
  });
  for (std::string& f : report.faults)
    if (f.find("std::bad_alloc") != std::string::npos)
      f += " (ran out of memory: a runaway allocation? the check's limit is " +
           accel::format_bytes(double(o.memory_bytes)) + ")";
  const json j = report_json(report, o);
  return accel::write_file_atomic(o.worker_report, j.dump(1) + "\n") ? 0 : kExitBadInput;
}

/// Runs the child for `structure`; returns its report, or one made of how it died.
json run_child(const std::string& structure, const CheckOptions& o, const std::string& self) {
  char dir_template[] = "/tmp/accelviz-check-XXXXXX";
  const char* dir = mkdtemp(dir_template);
  json failed = {{"structure", structure},
                 {"passed", false},
                 {"categories", json::array()},
                 {"wrong_rays", json::array()},
                 {"invariants", json::array()},
                 {"faults", json::array()},
                 {"speed", {{"timed", false}, {"why_not", "the check did not finish"}}}};
  if (!dir) {
    failed["failure"] = "cannot create a temporary folder";
    return failed;
  }
  const std::string progress_file = std::string(dir) + "/progress", report_file = std::string(dir) + "/report.json";
  SharedProgress* progress = nullptr;
  if (const int fd = ::open(progress_file.c_str(), O_RDWR | O_CREAT, 0600); fd >= 0) {
    if (::ftruncate(fd, sizeof(SharedProgress)) == 0) {
      void* p = ::mmap(nullptr, sizeof(SharedProgress), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
      if (p != MAP_FAILED) progress = static_cast<SharedProgress*>(p);
    }
    ::close(fd);
  }
  std::vector<std::string> args = {self,
                                   "check",
                                   "--structure",
                                   structure,
                                   "--worker-progress",
                                   progress_file,
                                   "--worker-report",
                                   report_file,
                                   "--out-dir",
                                   o.out_dir,
                                   "--shared",
                                   o.shared,
                                   "--ray-scale",
                                   fmt(o.ray_scale, "%.17g"),
                                   "--memory-limit",
                                   std::to_string(o.memory_bytes)};
  if (!o.time) args.push_back("--no-time");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const auto start = std::chrono::steady_clock::now();
  if (posix_spawn(&pid, self.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
    failed["failure"] = "cannot start the check's child process";
    return failed;
  }
  int status = 0;
  bool timed_out = false;
  for (;;) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (std::chrono::steady_clock::now() - start > std::chrono::duration<double>(o.timeout)) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::string where = progress ? std::string(progress->where) : "";
  const uint64_t ray = progress ? uint64_t(progress->ray) : 0;
  const std::string at =
      where.empty() ? "before the first case"
                    : "at " + where + (where.rfind("speed/", 0) == 0 ? " (timing)" : " ray " + std::to_string(ray));
  json result;
  std::ifstream in(report_file);
  if (!timed_out && WIFEXITED(status) && WEXITSTATUS(status) == 0 && in) {
    try {
      in >> result;
    } catch (const std::exception&) {
      result = json();
    }
  }
  if (result.is_null()) {
    result = failed;
    if (timed_out)
      result["failure"] = "no answer within the time limit of " + fmt(o.timeout, "%g") + " s " + at +
                          ": an endless loop? (--timeout sets the limit)";
    else if (WIFSIGNALED(status))
      result["failure"] = std::string("crashed (") + strsignal(WTERMSIG(status)) + ") " + at;
    else
      result["failure"] =
          "the check's child process exited with code " + std::to_string(WEXITSTATUS(status)) + " " + at;
    if (!where.empty() && where.rfind("speed/", 0) != 0) {
      result["failure_case"] = where;
      result["failure_ray"] = ray;
    }
  }
  if (progress) ::munmap(progress, sizeof(SharedProgress));
  std::error_code ec;
  fs::remove_all(dir, ec);
  return result;
}

void print_report(const json& r) {
  const std::string name = r.value("structure", "?");
  std::printf("== %s (student %s, compared with the built-in %s)%s\n", name.c_str(), r.value("kind", "?").c_str(),
              r.value("builtin", "?").c_str(),
              r.value("source", "").empty() ? "" : (" from " + r.value("source", "")).c_str());
  if (!r.value("failure", "").empty()) std::printf("FAILED: %s\n", r["failure"].get<std::string>().c_str());
  if (!r["categories"].empty()) {
    std::printf("%-12s %6s %9s %11s %10s %15s %8s\n", "category", "cases", "rays", "false miss", "false hit",
                "wrong triangle", "wrong t");
    for (const auto& c : r["categories"]) {
      const auto& w = c["wrong"];
      std::printf("%-12s %6zu %9zu %11zu %10zu %15zu %8zu\n", c["name"].get<std::string>().c_str(),
                  c["cases"].get<size_t>(), c["rays"].get<size_t>(), w["false_miss"].get<size_t>(),
                  w["false_hit"].get<size_t>(), w["wrong_triangle"].get<size_t>(), w["wrong_t"].get<size_t>());
    }
  }
  size_t k = 0;
  for (const auto& w : r["wrong_rays"]) {
    std::printf(
        "wrong %zu: %s/%s ray %zu: %s: answered %s, the reference %s\n", ++k, w["category"].get<std::string>().c_str(),
        w["case"].get<std::string>().c_str(), w["ray"].get<size_t>(), w["verdict"].get<std::string>().c_str(),
        w["got"]["prim"].get<int>() < 0 ? "miss"
                                        : ("triangle " + std::to_string(w["got"]["prim"].get<int>()) +
                                           " at t=" + fmt(w["got"]["t"].get<double>(), "%.9g"))
                                              .c_str(),
        w["reference"]["prim"].get<int>() < 0 ? "misses"
                                              : ("hits triangle " + std::to_string(w["reference"]["prim"].get<int>()) +
                                                 " at t=" + fmt(w["reference"]["t"].get<double>(), "%.9g"))
                                                    .c_str());
    if (!w.value("trap", "").empty()) std::printf("  the lecture's trap: %s\n", w["trap"].get<std::string>().c_str());
    if (w.contains("replay")) std::printf("  replay: %s\n", w["replay"].get<std::string>().c_str());
  }
  for (const auto& i : r["invariants"]) {
    if (!i["applies"].get<bool>()) continue;
    const size_t failed = i["failed"].get<size_t>();
    std::printf(
        "invariant: %-56s %s\n", i["name"].get<std::string>().c_str(),
        failed ? ("FAILED " + std::to_string(failed) + "x: " + i["first_failure"].get<std::string>()).c_str() : "ok");
  }
  for (const auto& f : r["faults"]) std::printf("fault: %s\n", f.get<std::string>().c_str());
  const auto& s = r["speed"];
  if (s.value("timed", false)) {
    auto ratio = [](double a, double b) { return b > 0 ? fmt(a / b, "%.2f") + "x" : std::string("-"); };
    const double m = s["mrays_per_s"], pm = s["builtin_mrays_per_s"], n = s["nodes_per_ray"],
                 pn = s["builtin_nodes_per_ray"], t = s["triangles_per_ray"], pt = s["builtin_triangles_per_ray"];
    std::printf("speed (%s): %s Mrays/s (%s of the built-in's %s), nodes/ray %s (%s), triangles/ray %s (%s)\n",
                s["workload"].get<std::string>().c_str(), fmt(m, "%.3g").c_str(), ratio(m, pm).c_str(),
                fmt(pm, "%.3g").c_str(), fmt(n, "%.3g").c_str(), ratio(n, pn).c_str(), fmt(t, "%.3g").c_str(),
                ratio(t, pt).c_str());
  } else {
    std::printf("speed: not timed: %s\n", s.value("why_not", "").c_str());
  }
  std::printf("%s: %s\n", name.c_str(),
              r.value("passed", false) ? "PASSED (every answer right, every invariant kept)" : "FAILED");
}

}  // namespace

int run_check(const CheckOptions& options) {
  CheckOptions o = options;
  if (!o.memory_limit.empty()) {
    auto bytes = accel::parse_memory_size(o.memory_limit, "--memory-limit");
    if (!bytes) {
      std::fprintf(stderr, "accelviz-cli: check: %s\n", bytes.error().message.c_str());
      return kExitBadInput;
    }
    o.memory_bytes = bytes.value();
  }
  if (!o.worker_report.empty()) return run_worker(o);
  if (!(o.ray_scale > 0.0 && o.ray_scale <= 10.0)) {
    std::fprintf(stderr, "accelviz-cli: check: --ray-scale must be in (0, 10]\n");
    return kExitBadInput;
  }
  std::vector<std::string> names;
  if (!o.structure.empty()) {
    auto info = accel::find_structure(o.structure);
    if (!info) {
      std::fprintf(stderr, "accelviz-cli: check: %s\n", info.error().message.c_str());
      return kExitBadInput;
    }
    if (!info.value()->student) {
      std::fprintf(stderr, "accelviz-cli: check: '%s' is a built-in structure; check takes a student structure (%s)\n",
                   o.structure.c_str(), "built in with scripts/run.sh --student DIR, docs/student.md");
      return kExitBadInput;
    }
    names.push_back(o.structure);
  } else {
    for (const accel::StructureInfo* s : accel::student_structures()) names.push_back(s->name);
    if (names.empty()) {
      std::fprintf(stderr,
                   "accelviz-cli: check: no student structure is built in (build with scripts/run.sh --student DIR "
                   "or -DACCEL_STUDENT_DIR=DIR; docs/student.md)\n");
      return kExitBadInput;
    }
  }
  std::error_code ec;
  const std::string self = fs::read_symlink("/proc/self/exe", ec).native();
  json all = {{"structures", json::array()}};
  bool passed = true;
  for (const std::string& name : names) {
    if (!o.json) std::fprintf(stderr, "checking %s ...\n", name.c_str());
    json r = run_child(name, o, self);
    passed = passed && r.value("passed", false);
    if (!o.json) print_report(r);
    all["structures"].push_back(std::move(r));
  }
  all["passed"] = passed;
  if (o.json) std::printf("%s\n", all.dump(1).c_str());
  return passed ? 0 : 1;
}

}  // namespace cli
