// accelviz-cli check: the assignment kit's grader (docs/student.md), as a judge that holds no
// student code. The student's structures live in a worker program (accelviz-worker, or one
// compiled from --submission DIR in the sandbox); the judge starts it confined
// (judge/confinement.h), asks it for its structures, and runs the core's grader with proxy
// student objects (judge/remote_student.h): the worker only ever sends what the student's
// code did, and the judge decides every verdict, writes every file and sets the exit code.
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
#include "judge/confinement.h"
#include "judge/grading.h"
#include "judge/remote_student.h"
#include "platform_formats.h"
#include "memory_budget.h"
#include "rays_io.h"
#include "registry.h"
#include "student/grader.h"

extern char** environ;

namespace cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

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

/// Text that the student's code printed, made valid UTF-8 (other bytes as \xNN), so a report
/// never fails to be written for a byte a student chose.
std::string utf8_or_escaped(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const size_t len = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    bool ok = len > 0 && i + len <= s.size();
    for (size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(s[i + k]) >> 6) == 2;
    if (ok && (c >= 0x20 || c == '\n' || c == '\t')) {
      out.append(s, i, len);
      i += len;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
      ++i;
    }
  }
  return out;
}

/// The viewer that holds the student's code, as a command a person types from the current
/// folder: the one built beside the worker (accelviz-worker -> accelviz; the kit tests'
/// accelviz-worker-kit -> accelviz-kit).
std::string viewer_beside(const std::string& worker) {
  fs::path exe(worker);
  std::string name = exe.filename().native();
  if (const size_t at = name.find("-worker"); at != std::string::npos) name.erase(at, 7);
  fs::path viewer = exe.parent_path() / name;
  std::error_code ec;
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

}  // namespace

json report_json(const accel::CheckReport& r, const std::string& out_dir, const std::string& viewer,
                 const judge::WorkerBudget& budget) {
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
  const std::string dir = (fs::path(out_dir) / r.structure).native();
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
      jw["replay"] = viewer + " --restore " + state;
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
  j["failure"] = r.failure;
  j["sandbox"] = describe_confinement(budget.confinement);
  // What the student's code printed: data, shown quoted, never read for a verdict.
  j["output"] = utf8_or_escaped(budget.output());
  j["output_bytes"] = budget.output_bytes();
  j["passed"] = r.passed();
  return j;
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
  // What the student's code printed is quoted line by line: it can say anything, "PASSED"
  // included, and must never read as the judge's words.
  if (r.value("output_bytes", size_t(0)) > 0) {
    std::printf("the student's code printed %zu bytes; the first lines, quoted:\n", r.value("output_bytes", size_t(0)));
    std::string out = r.value("output", "");
    size_t lines = 0, at = 0;
    while (at < out.size() && lines < 12) {
      const size_t nl = out.find('\n', at);
      std::printf("  | %s\n", out.substr(at, std::min<size_t>(nl == std::string::npos ? out.npos : nl - at, 200)).c_str());
      at = nl == std::string::npos ? out.size() : nl + 1;
      ++lines;
    }
  }
  std::printf("sandbox: %s\n", r.value("sandbox", "").c_str());
  std::printf("%s: %s\n", name.c_str(),
              r.value("passed", false) ? "PASSED (every answer right, every invariant kept)" : "FAILED");
}

/// A report for a structure, or a whole worker, that could not be checked at all.
json failed_report(const std::string& structure, const std::string& failure, const judge::WorkerBudget& budget) {
  return {{"structure", structure},
          {"passed", false},
          {"failure", failure},
          {"categories", json::array()},
          {"wrong_rays", json::array()},
          {"invariants", json::array()},
          {"faults", json::array()},
          {"speed", {{"timed", false}, {"why_not", "the check did not run"}}},
          {"sandbox", describe_confinement(budget.confinement)},
          {"output", utf8_or_escaped(budget.output())},
          {"output_bytes", budget.output_bytes()}};
}

accel::Result<json> check_worker(const std::shared_ptr<judge::WorkerBudget>& budget, const accel::CheckOptions& co,
                                 const std::string& only, const std::string& out_dir, const std::string& viewer) {
  json reports = json::array();
  budget->start_check();
  auto listed = judge::list_worker(budget);
  if (!listed) {
    // Its static initialisers ran (in the sandbox) and it never answered: that is the report.
    reports.push_back(failed_report(only.empty() ? "(the worker)" : only,
                                    "the structures could not be listed: " + listed.error().message, *budget));
    return reports;
  }
  std::vector<accel::StructureInfo> infos;
  for (const accel::StudentEntry& entry : judge::remote_entries(listed.value(), budget)) {
    auto info = accel::student_structure_info(entry, accel::structure_registry());
    if (!info) return info.error();
    infos.push_back(std::move(info.value()));
  }
  if (!only.empty()) {
    auto it = std::find_if(infos.begin(), infos.end(), [&](const auto& i) { return i.name == only; });
    if (it == infos.end()) {
      if (accel::find_structure(only))
        return accel::make_error("'" + only +
                                 "' is a built-in structure; check takes a student structure (built in with "
                                 "scripts/run.sh --student DIR, docs/student.md)");
      return accel::make_error("unknown structure '" + only + "' (the worker holds: " +
                               [&] {
                                 std::string names;
                                 for (const auto& i : infos) names += (names.empty() ? "" : ", ") + i.name;
                                 return names.empty() ? std::string("none") : names;
                               }() +
                               ")");
    }
    infos = {*it};
  }
  if (infos.empty()) return accel::make_error("the worker " + budget->worker + " holds no student structure");
  for (const accel::StructureInfo& info : infos) {
    // The replays of an earlier check of this structure would be mistaken for this one's.
    std::error_code ec;
    fs::remove_all(fs::path(out_dir) / info.name, ec);
    budget->start_check();
    accel::CheckReport report = accel::check_structure(info, co, [](const std::string&, size_t) {});
    for (std::string& f : report.faults)
      if (f.find("std::bad_alloc") != std::string::npos)
        f += " (ran out of memory: a runaway allocation? the worker's limit is " +
             accel::format_bytes(double(budget->confinement.memory_bytes)) + ")";
    reports.push_back(report_json(report, out_dir, viewer, *budget));
  }
  return reports;
}

std::string worker_beside_cli() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : (exe.parent_path() / "accelviz-worker").native();
}

std::shared_ptr<judge::WorkerBudget> make_budget(const std::string& worker, const CheckOptions& o) {
  auto budget = std::make_shared<judge::WorkerBudget>();
  std::error_code ec;
  budget->worker = fs::canonical(worker, ec).native();
  if (ec) budget->worker = worker;
  budget->timeout_seconds = o.timeout;
  budget->confinement.sandbox = o.sandbox;
  budget->confinement.memory_bytes = o.memory_bytes;
  budget->confinement.cpu_seconds = o.timeout * 2.0 + 10.0;  // every core may spin: the wall limit stops it first
  budget->confinement.read_only = {budget->worker};
  return budget;
}

accel::CheckOptions grader_options(const CheckOptions& o) {
  accel::CheckOptions co;
  co.shared_scenes = o.shared;
  co.ray_scale = o.ray_scale;
  co.time = o.time;
  return co;
}

int print_reports(const json& reports, const std::string& format, const json& compile) {
  bool passed = !reports.empty();
  for (const auto& r : reports) passed = passed && r.value("passed", false);
  if (format == "json") {
    json all = {{"structures", reports}, {"passed", passed}};
    if (!compile.is_null()) all["compile"] = compile;
    std::printf("%s\n", all.dump(1, ' ', false, json::error_handler_t::replace).c_str());
  } else if (format == "gradescope" || format == "prairielearn") {
    json student = {{"structures", reports}, {"passed", passed}, {"compile", compile.is_null() ? json{{"ok", true}} : compile}};
    const json out = format == "gradescope" ? gradescope_results(student) : prairielearn_results(student);
    std::printf("%s\n", out.dump(1, ' ', false, json::error_handler_t::replace).c_str());
  } else {
    if (!compile.is_null() && !compile.value("ok", true))
      std::printf("compile error:\n%s\n", compile.value("error", "").c_str());
    for (const auto& r : reports) print_report(r);
  }
  return passed ? 0 : 1;
}

int prepare_judge_options(CheckOptions& o, const char* command) {
  if (!o.memory_limit.empty()) {
    auto bytes = accel::parse_memory_size(o.memory_limit, "--memory-limit");
    if (!bytes) {
      std::fprintf(stderr, "accelviz-cli: %s: %s\n", command, bytes.error().message.c_str());
      return kExitBadInput;
    }
    o.memory_bytes = bytes.value();
  }
  if (!(o.ray_scale > 0.0 && o.ray_scale <= 10.0)) {
    std::fprintf(stderr, "accelviz-cli: %s: --ray-scale must be in (0, 10]\n", command);
    return kExitBadInput;
  }
  if (o.sandbox && !judge::sandbox_unavailable_reason().empty()) {
    std::fprintf(stderr, "accelviz-cli: %s: refusing to grade: %s (--no-sandbox runs the student's code without it)\n",
                 command, judge::sandbox_unavailable_reason().c_str());
    return kExitNoSandbox;
  }
  return 0;
}

int run_check(const CheckOptions& options) {
  CheckOptions o = options;
  if (const int bad = prepare_judge_options(o, "check")) return bad;
  if (o.json) o.format = "json";
  std::string worker = o.worker.empty() ? worker_beside_cli() : o.worker;
  std::string viewer = viewer_beside(worker);
  json compile;
  if (!o.submission.empty()) {
    const Submission sub = compile_submission(o.submission, o.out_dir + "/.build", o);
    if (!sub.error_for_user.empty()) {
      std::fprintf(stderr, "accelviz-cli: check: %s\n", sub.error_for_user.c_str());
      return kExitBadInput;
    }
    compile = sub.compile;
    if (!sub.compile.value("ok", false)) return print_reports(json::array(), o.format, compile);
    worker = sub.worker;
    viewer = "scripts/run.sh --student " + o.submission;
  } else if (worker.empty() || access(worker.c_str(), X_OK) != 0) {
    std::fprintf(stderr,
                 "accelviz-cli: check: no student structure is built in: %s is missing (build with scripts/run.sh "
                 "--student DIR or -DACCEL_STUDENT_DIR=DIR, or give --submission DIR; docs/student.md)\n",
                 worker.empty() ? "accelviz-worker" : worker.c_str());
    return kExitBadInput;
  }
  auto budget = make_budget(worker, o);
  auto reports = check_worker(budget, grader_options(o), o.structure, o.out_dir, viewer);
  if (!reports) {
    std::fprintf(stderr, "accelviz-cli: check: %s\n", reports.error().message.c_str());
    return kExitBadInput;
  }
  return print_reports(reports.value(), o.format, compile);
}

}  // namespace cli
