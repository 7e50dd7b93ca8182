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
#include "student/walk_audit.h"
#include "text_format.h"

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

/// "miss" / "triangle 12 at t=0.5" (`verb` before a hit: "hits ").
std::string hit_text(const json& h, const std::string& verb) {
  if (h.value("prim", -1) < 0 || h["t"].is_null()) return verb.empty() ? "miss" : "misses";
  return verb + "triangle " + std::to_string(h["prim"].get<int64_t>()) + " at t=" + fmt(h["t"].get<double>(), "%.9g");
}

/// A hit in --json: a miss is prim -1 and t null (JSON has no infinity; docs/student.md).
json hit_json(int64_t prim, bool hit, double t) {
  return {{"prim", hit ? prim : int64_t(-1)}, {"t", hit ? json(t) : json(nullptr)}};
}

/// The causes that are the lecture's traps (the class report counts students per trap).
bool is_lecture_trap(const std::string& cause) {
  return cause != "unexplained" && cause != "fault" && cause != "skipped" && cause != "nothing_built";
}

/// The scene of a wrong ray or a failed build as a file the viewer opens: procedural scenes
/// by name, the others written as OBJ beside the state ("" for an empty scene).
std::string replay_scene(const std::string& category, const std::string& case_name, const accel::Scene& scene,
                         const std::string& dir, std::string* error) {
  if (category == "procedural") return "procedural:" + case_name;
  if (scene.triangle_count() == 0) return "";
  const std::string path = fs::absolute(fs::path(dir) / (safe_name(category + "_" + case_name) + ".obj")).native();
  if (!fs::exists(path))
    if (auto s = accel::write_scene_obj(scene, path); !s) {
      *error = s.error().message;
      return "";
    }
  return path;
}

/// Writes DIR/FILE, a viewer state: `header` (comment lines), the case's scene (generated
/// scenes written beside it as OBJ), then `commands`. "" and `error` when it cannot.
std::string write_state(const std::string& dir, const std::string& file, const std::string& category,
                        const std::string& case_name, const accel::Scene& scene, const std::string& header,
                        const std::string& commands, std::string* error) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    *error = dir + ": cannot create the folder: " + ec.message();
    return "";
  }
  const std::string scene_arg = replay_scene(category, case_name, scene, dir, error);
  if (scene_arg.empty()) return "";
  const std::string state = (fs::path(dir) / file).native();
  if (auto s = accel::write_file_atomic(state, header + "scene " + scene_arg + "\n" + commands); !s) {
    *error = s.error().message;
    return "";
  }
  return state;
}

/// The replay of a failed build: a state that plays the construction up to the build-log
/// call where it failed.
std::string write_build_replay(const accel::BuildFault& f, const std::string& structure, const std::string& dir,
                               size_t k, std::string* error) {
  std::string what = f.what;
  for (char& c : what)
    if (c == '\n' || c == '\r') c = ' ';
  return write_state(dir, "build_fault" + std::to_string(k) + ".state", f.category, f.case_name, *f.scene,
                     "# accelviz-cli check: " + structure + ", " + f.category + "/" + f.case_name + ": " + what +
                         "\n# " + f.node + "\n",
                     "structure " + structure + "\nconstruct-until " + std::to_string(f.log_calls) + "\n", error);
}

/// The replay of one wrong ray: the scene, the structure, the ray (its tmin and tmax as C99
/// hex floats) and the step of its cause.
std::string write_replay(const accel::WrongRay& w, const std::string& structure, const std::string& dir, size_t k,
                         std::string* error) {
  return write_state(dir, "wrong" + std::to_string(k) + ".state", w.category, w.case_name, *w.scene,
                     "# accelviz-cli check: " + structure + ", " + w.category + "/" + w.case_name + " ray " +
                         std::to_string(w.index) + ": " + kVerdictKeys[int(w.verdict)] + ": " + w.cause + "\n",
                     "structure " + structure + "\nray " + accel::format_ray_line(w.ray) + "\n" +
                         (w.step != size_t(-1) && w.step > 0 ? "step " + std::to_string(w.step) + "\n" : ""),
                     error);
}

/// The causes of the wrong rays, the most rays first, each with its examples (their replays
/// written under `dir`); every example is also one of `wrong_rays`.
void add_causes_json(json& j, const accel::CheckReport& r, const std::string& dir, const std::string& viewer) {
  j["causes"] = json::array();
  j["wrong_rays"] = json::array();
  size_t k = 0;
  for (const accel::CheckCause& c : r.causes) {
    const accel::CauseInfo& info = accel::cause_info(c.id);
    json jc = {{"cause", c.id}, {"title", info.title}, {"lecture", info.lecture}, {"rays", c.rays}};
    jc["cases"] = json::array();
    for (const auto& [where, n] : c.cases) jc["cases"].push_back({{"case", where}, {"rays", n}});
    jc["examples"] = json::array();
    for (const accel::WrongRay& w : c.examples) {
      std::string error;
      const std::string state = write_replay(w, r.structure, dir, ++k, &error);
      json jw = {{"category", w.category},
                 {"case", w.case_name},
                 {"ray", w.index},
                 {"verdict", kVerdictKeys[int(w.verdict)]},
                 {"got", hit_json(w.got.prim, w.got.valid(), double(w.got.t))},
                 {"reference", hit_json(w.ref.prim, w.ref.prim >= 0, w.ref.t)},
                 {"cause", w.cause},
                 {"title", info.title},
                 {"detail", w.detail},
                 {"trap", is_lecture_trap(w.cause) ? info.title : ""}};
      if (w.step != size_t(-1)) jw["step"] = w.step;
      if (!state.empty()) {
        jw["state_file"] = state;
        jw["replay"] = viewer + " --restore " + state;
      } else if (!error.empty()) {
        jw["replay_error"] = error;
      }
      jc["examples"].push_back(jw);
      j["wrong_rays"].push_back(jw);
    }
    j["causes"].push_back(jc);
  }
}

/// The failed builds, each with its replay (written under `dir`).
json build_faults_json(const accel::CheckReport& r, const std::string& dir, const std::string& viewer) {
  json out = json::array();
  for (size_t b = 0; b < r.build_faults.size(); ++b) {
    const accel::BuildFault& f = r.build_faults[b];
    json jf = {{"case", f.category + "/" + f.case_name}, {"what", f.what}, {"node", f.node}, {"build_calls", f.log_calls}};
    std::string error;
    const std::string state = write_build_replay(f, r.structure, dir, b + 1, &error);
    if (!state.empty()) {
      jf["state_file"] = state;
      jf["replay"] = viewer + " --restore " + state;
    } else if (!error.empty()) {
      jf["replay_error"] = error;
    }
    out.push_back(jf);
  }
  return out;
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
    j["categories"].push_back({{"name", c.name},
                               {"cases", c.cases},
                               {"rays", c.rays},
                               {"wrong", wrong},
                               {"skipped_cases", c.skipped_cases},
                               {"skipped_rays", c.skipped_rays}});
  }
  j["cases"] = json::array();
  for (const auto& c : r.cases)
    j["cases"].push_back(
        {{"case", c.category + "/" + c.name}, {"rays", c.rays}, {"wrong", c.wrong}, {"skipped", c.skipped}});
  const std::string dir = (fs::path(out_dir) / r.structure).native();
  add_causes_json(j, r, dir, viewer);
  j["build_faults"] = build_faults_json(r, dir, viewer);
  j["notices"] = r.notices;
  j["waste"] = {{"measured", r.waste.measured}, {"compared_with", r.waste.peer}, {"over_limit", r.waste.over_limit}};
  j["waste"]["findings"] = json::array();
  for (const accel::WasteFinding& f : r.waste.findings)
    j["waste"]["findings"].push_back(
        {{"name", f.name}, {"value", f.value}, {"limit", f.limit}, {"sentence", f.sentence}, {"over", f.over}});
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

namespace {

/// Each cause: its rays, the cases, its example rays with their why and replay; then the
/// wrong answers per case.
void print_causes(const json& r) {
  const json causes = r.value("causes", json::array());
  if (!causes.empty())
    std::printf("wrong answers by cause (%zu cause%s; each cause's first rays, from the cases with the most):\n",
                causes.size(), causes.size() == 1 ? "" : "s");
  size_t k = 0, c_index = 0;
  for (const auto& c : causes) {
    const json cases = c.value("cases", json::array());
    std::printf("cause %zu: %s rays in %zu case%s: %s\n", ++c_index, accel::with_separators(c.value("rays", size_t(0))).c_str(),
                cases.size(), cases.size() == 1 ? "" : "s", c.value("title", "").c_str());
    std::printf("  lecture: %s\n", c.value("lecture", "").c_str());
    std::string most;
    for (size_t i = 0; i < cases.size() && i < 4; ++i)
      most += (i ? ", " : "") + cases[i].value("case", "") + " " + accel::with_separators(cases[i].value("rays", size_t(0)));
    if (cases.size() > 4) most += ", and " + std::to_string(cases.size() - 4) + " more";
    std::printf("  in: %s\n", most.c_str());
    for (const auto& w : c.value("examples", json::array())) {
      std::printf("  wrong %zu: %s/%s ray %zu: %s: answered %s, the reference %s\n", ++k,
                  w["category"].get<std::string>().c_str(), w["case"].get<std::string>().c_str(),
                  w["ray"].get<size_t>(), w["verdict"].get<std::string>().c_str(), hit_text(w["got"], "").c_str(),
                  hit_text(w["reference"], "hits ").c_str());
      if (!w.value("detail", "").empty()) std::printf("    why: %s\n", w["detail"].get<std::string>().c_str());
      if (w.contains("replay")) std::printf("    replay: %s\n", w["replay"].get<std::string>().c_str());
    }
  }
  if (!causes.empty()) {
    std::string per_case;
    size_t shown = 0, with_wrong = 0;
    for (const auto& c : r.value("cases", json::array())) {
      if (c.value("wrong", size_t(0)) == 0) continue;
      ++with_wrong;
      if (shown++ < 12)
        per_case += (per_case.empty() ? "" : ", ") + c.value("case", "") + " " +
                    accel::with_separators(c.value("wrong", size_t(0))) + "/" + accel::with_separators(c.value("rays", size_t(0)));
    }
    if (with_wrong > shown) per_case += ", and " + std::to_string(with_wrong - shown) + " more";
    std::printf("wrong answers per case: %s\n", per_case.c_str());
  }
}

void print_build_faults_and_waste(const json& r) {
  for (const auto& f : r.value("build_faults", json::array())) {
    std::printf("build fault: %s: %s\n  the node being built: %s\n", f.value("case", "").c_str(),
                f.value("what", "").c_str(), f.value("node", "").c_str());
    if (f.contains("replay"))
      std::printf("  replay (plays the construction up to the fault): %s\n", f["replay"].get<std::string>().c_str());
  }
  const json waste = r.value("waste", json::object());
  if (waste.value("measured", false)) {
    const json findings = waste.value("findings", json::array());
    if (findings.empty()) {
      std::printf("waste: none worth saying against the built-in %s\n", waste.value("compared_with", "").c_str());
    } else {
      std::printf("waste (right answers, but against the built-in %s):\n", waste.value("compared_with", "").c_str());
      for (const auto& f : findings)
        std::printf("  %s%s\n", f.value("over", false) ? "OVER THE --strict LIMIT: " : "",
                    f.value("sentence", "").c_str());
    }
  }
}

/// The speed against the built-in, and what the student's code printed, quoted.
void print_speed_and_output(const json& r) {
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
}

}  // namespace

void print_report(const json& r) {
  const std::string name = r.value("structure", "?");
  std::printf("== %s (student %s, compared with the built-in %s)%s\n", name.c_str(), r.value("kind", "?").c_str(),
              r.value("builtin", "?").c_str(),
              r.value("source", "").empty() ? "" : (" from " + r.value("source", "")).c_str());
  if (!r.value("failure", "").empty()) std::printf("FAILED: %s\n", r["failure"].get<std::string>().c_str());
  if (!r["categories"].empty()) {
    std::printf("%-12s %6s %9s %11s %10s %15s %8s %8s\n", "category", "cases", "rays", "false miss", "false hit",
                "wrong triangle", "wrong t", "skipped");
    for (const auto& c : r["categories"]) {
      const auto& w = c["wrong"];
      std::printf("%-12s %6zu %9zu %11zu %10zu %15zu %8zu %8zu\n", c["name"].get<std::string>().c_str(),
                  c["cases"].get<size_t>(), c["rays"].get<size_t>(), w["false_miss"].get<size_t>(),
                  w["false_hit"].get<size_t>(), w["wrong_triangle"].get<size_t>(), w["wrong_t"].get<size_t>(),
                  c.value("skipped_rays", size_t(0)));
    }
  }
  for (const auto& n : r.value("notices", json::array())) std::printf("notice: %s\n", n.get<std::string>().c_str());
  print_causes(r);
  print_build_faults_and_waste(r);
  for (const auto& i : r["invariants"]) {
    if (!i["applies"].get<bool>()) continue;
    const size_t failed = i["failed"].get<size_t>();
    std::printf(
        "invariant: %-56s %s\n", i["name"].get<std::string>().c_str(),
        failed ? ("FAILED " + std::to_string(failed) + "x: " + i["first_failure"].get<std::string>()).c_str() : "ok");
  }
  for (const auto& f : r["faults"]) std::printf("fault: %s\n", f.get<std::string>().c_str());
  print_speed_and_output(r);
  std::printf("sandbox: %s\n", r.value("sandbox", "").c_str());
  std::printf("%s: %s\n", name.c_str(),
              r.value("passed", false) ? "PASSED (every answer right, every invariant kept)"
              : r.value("wrong", size_t(0)) == 0 && r.value("failure", "").empty() && r["faults"].empty() &&
                      r.value("waste", json::object()).value("over_limit", false)
                  ? "FAILED (--strict: waste over a limit)"
                  : "FAILED");
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
    accel::CheckOptions with_timing = co;
    // The timing has its own time limit: a check that used most of it still gets timed,
    // and a timing cut short never takes the correctness report with it.
    with_timing.before_timing = [&budget] { budget->restart_deadline(); };
    accel::CheckReport report = accel::check_structure(info, with_timing, [](const std::string&, size_t) {});
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
  co.strict = o.strict;
  for (const std::string& l : o.limits) accel::set_waste_limit(co.limits, l);  // validated before
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
  accel::WasteLimits limits;
  for (const std::string& l : o.limits)
    if (const std::string bad = accel::set_waste_limit(limits, l); !bad.empty()) {
      std::fprintf(stderr, "accelviz-cli: %s: %s\n", command, bad.c_str());
      return kExitBadInput;
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
