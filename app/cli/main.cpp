// accelviz-cli: answers ray queries in batch and reports structure statistics.
//   accelviz-cli trace --scene FILE.obj --structure S [--param k=v]... --rays RAYS --out HITS.csv
//   accelviz-cli stats --scene FILE.obj --structure S [--param k=v]... [--json]
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <string>

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <climits>
#include <csignal>
#include <cstdlib>
#include <memory>

#include "commands.h"
#include "judge/grading.h"
#include "judge/remote_student.h"
#include "student/kit_registry.h"
#include "interrupt.h"
#include "memory_budget.h"
#include "registry.h"
#include "scene.h"
#include "tinybvh_baseline.h"
#include "warm_start.h"

namespace {

std::string join(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : "|") + i;
  return s;
}

/// --memory-limit and --time-limit, the budget of every build (memory_budget.h).
void add_limit_options(CLI::App* cmd, std::string* memory_limit, double* time_limit) {
  cmd->add_option("--memory-limit", *memory_limit,
                  "memory a build may use, e.g. 4G, 512M or 25% (default: " +
                      std::to_string(int(accel::kDefaultMemoryFraction * 100)) + "% of physical memory, " +
                      accel::format_bytes(double(accel::default_memory_limit())) + " here)");
  cmd->add_option("--time-limit", *time_limit, "seconds a build may take before it stops with an error (0 = none)")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
}

void add_structure_options(CLI::App* cmd, cli::StructureOptions* o) {
  cmd->add_option("--scene", o->scene, "mesh file (OBJ, PLY, STL, glTF, GLB), or procedural:NAME (" + join(accel::procedural_scene_names()) + ")")
      ->required();
  cmd->add_option("--structure", o->structure, "acceleration structure: " + join(accel::structure_names()))
      ->capture_default_str();
  cmd->add_option("--param", o->params, "structure parameter key=value (repeatable); see 'accelviz-cli params'");
  cmd->add_option("--kernel", o->kernel, "ray/triangle test: " + accel::kernel_names_text("|"))->capture_default_str();
  add_limit_options(cmd, &o->memory_limit, &o->time_limit);
}

/// The options check and grade-class share: what a student structure is checked on, and
/// how its code is confined.
void add_judge_options(CLI::App* cmd, cli::CheckOptions* o) {
  cmd->add_option("--shared", o->shared, "folder of the shared meshes (skipped when absent)")->capture_default_str();
  cmd->add_option("--ray-scale", o->ray_scale, "multiply every case's ray count (0 < F <= 10)")->capture_default_str();
  cmd->add_flag("!--no-time", o->time, "skip the speed measurement");
  cmd->add_flag("--strict", o->strict,
                "also fail a right structure that wastes past a limit against its built-in (--limit; for course "
                "autograders: the default is correctness only)");
  cmd->add_option("--limit", o->limits,
                  "NAME=VALUE (repeatable): --strict's limits, uncrossed=0.25 (share of visited nodes the ray does "
                  "not cross), triangles=3, leaf_size=4, references=3 (multiples of the built-in's); 0: none");
  cmd->add_option("--timeout", o->timeout, "seconds one structure's check may take (an endless loop)")
      ->check(CLI::Range(1.0, 86400.0))
      ->capture_default_str();
  cmd->add_option("--memory-limit", o->memory_limit,
                  "memory one structure's worker may use, e.g. 2G (default: 4G or half the memory)");
  cmd->add_flag("!--no-sandbox", o->sandbox,
                "run the student's code without bubblewrap (where a course platform's container isolates it): "
                "limits and seccomp only, as the user nobody when run as root; the report says so");
}

int print_params() {
  for (const auto& info : accel::structure_registry()) {
    std::printf("%s: %s\n", info.name.c_str(), info.description.c_str());
    for (const auto& p : info.params)
      std::printf("  %-12s default %-10s %s; %s\n", p.name.c_str(), p.default_value.c_str(), p.range_text().c_str(),
                  p.doc.c_str());
  }
  return 0;
}

/// The command's exit code, or 2 when its standard output could not be written (a full disk,
/// a closed pipe): a table that did not arrive is not a success.
int check_stdout(int code) {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return code;
  if (code != 0) return code;  // the command already said what went wrong
  std::fprintf(stderr, "accelviz-cli: standard output: write failed%s%s\n", errno ? ": " : "",
               errno ? std::strerror(errno) : "");
  return cli::kExitBadInput;
}

/// trace: the closest hit of every ray, as a hits CSV.
CLI::App* add_trace_command(CLI::App& app, cli::TraceOptions* o) {
  CLI::App* cmd = app.add_subcommand("trace", "closest hit for every ray of a rays file (docs/hits.md CSV out)");
  add_structure_options(cmd, &o->build);
  cmd->add_option("--rays", o->rays, "rays file (docs/hits.md), or primary:W:H, or random:N:SEED")->required();
  cmd->add_option("--out", o->out, "hits CSV to write")->required();
  cmd->add_option("--threads", o->threads, "worker threads (0 = all cores)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  return cmd;
}

/// stats: a structure's statistics, and optionally its rays' counters and its recorded build.
CLI::App* add_stats_command(CLI::App& app, cli::StatsOptions* o) {
  CLI::App* cmd = app.add_subcommand("stats", "build a structure and print its statistics");
  add_structure_options(cmd, &o->build);
  cmd->add_flag("--json", o->json, "print JSON instead of text");
  cmd->add_option("--rays", o->rays,
                  "also trace these rays (file, primary:W:H or random:N:SEED) and report nodes visited and "
                  "triangles tested per ray, and the time with the counters off (trace_fast_ms) and on");
  cmd->add_option("--threads", o->threads, "worker threads for --rays (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--build-trace", o->build_trace,
                  "also record the construction step by step and write it as JSON lines (docs/build-trace.md)");
  cmd->add_flag("--digest", o->digest,
               "also print a digest of the structure (every node and leaf as the views show them): equal "
               "digests, the same tree");
  cmd->add_option("--build-trace-budget", o->build_trace_budget_mb,
                  "MB of recorded steps; a bigger build is recorded to the depth that fits")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  return cmd;
}

/// bench: speed against error of every structure and the peers.
CLI::App* add_bench_command(CLI::App& app, cli::BenchOptions* o) {
  CLI::App* cmd = app.add_subcommand(
      "bench", "speed against error: build ms, MB, Mrays/s (1 and all threads), errors vs the double reference");
  cmd->add_option("--scene", o->scenes, "mesh file (OBJ, PLY, STL, glTF, GLB) or procedural:NAME (repeatable)")->required();
  cmd->add_option("--structures", o->structures, "comma list, or all (every structure except brute)")
      ->capture_default_str();
  cmd->add_option("--param", o->params,
                  "key=value for every structure that has the key, or STRUCTURE:key=value (repeatable)");
  cmd->add_option("--rays", o->rays, "primary:W:H, random:N:SEED or a rays file")->capture_default_str();
  cmd->add_option("--threads", o->threads, "threads of the multi-threaded run (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--kernel", o->kernels, "comma list of " + accel::kernel_names_text())->capture_default_str();
  cmd->add_option("--min-time", o->min_time, "seconds each of the 3 timing samples lasts at least")
      ->check(CLI::Range(0.001, 60.0))
      ->capture_default_str();
  add_limit_options(cmd, &o->memory_limit, &o->time_limit);
  cmd->add_option("--out-md", o->out_md, "write the table as Markdown");
  cmd->add_option("--out-csv", o->out_csv, "write the rows as CSV");
  cmd->add_option("--out-json", o->out_json, "write the rows as a JSON array");
  cmd->add_flag("!--no-embree", o->embree, "skip the Embree baseline rows");
  cmd->add_flag("--embree-robust", o->embree_robust,
                "add an embree-robust row: Embree's robust mode (RTC_SCENE_FLAG_ROBUST), medium quality");
  cmd->add_flag("!--no-tinybvh", o->tinybvh,
                cli::tinybvh_available() ? "skip the tinybvh peer rows (tinybvh-bvh8, tinybvh-bvh4, tinybvh-bvh8-hq)"
                                         : "skip the tinybvh peer rows (this binary has no tinybvh)");
  return cmd;
}

/// build-vs-embree: the default BVH's cold build against Embree medium's, in fresh processes.
CLI::App* add_build_vs_embree_command(CLI::App& app, cli::BuildVsEmbreeOptions* o) {
  CLI::App* cmd = app.add_subcommand(
      "build-vs-embree", "cold builds: the default BVH's first build in a fresh process against Embree medium's "
                         "(median of --runs processes each; ratio > 1: accelviz builds faster)");
  cmd->add_option("--scene", o->scenes, "mesh file or procedural:NAME (repeatable)")->required();
  cmd->add_option("--runs", o->runs, "fresh processes per side and scene")->check(CLI::Range(1, 100))->capture_default_str();
  cmd->add_option("--threads", o->threads, "build threads of both sides (0 = all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--out-json", o->out_json, "write the rows as a JSON array");
  cmd->add_option("--out-md", o->out_md, "write the table as Markdown");
  // The children this command starts: one side's builds in a fresh process, one JSON line out.
  cmd->add_option("--child", o->child)->check(CLI::IsMember({"accelviz", "embree"}))->group("");
  return cmd;
}

/// check: the assignment kit's grader over one or every student structure.
CLI::App* add_check_command(CLI::App& app, cli::CheckOptions* o) {
  o->shared = ACCEL_DEFAULT_SHARED_SCENES;
  o->memory_bytes = std::min<size_t>(size_t(4) << 30, accel::default_memory_limit());
  CLI::App* cmd = app.add_subcommand(
      "check", "grade student structures (docs/student.md): answers against the reference, the lecture's traps, "
               "invariants of the logs, speed against the built-in structure; exit 0 only when all is correct "
               "(1: not, 2: bad use, 3: no sandbox here)");
  add_judge_options(cmd, o);
  cmd->add_option("--structure", o->structure, "one student structure (default: every one the worker holds)");
  cmd->add_flag("--json", o->json, "print the report as JSON (the same as --format json)");
  cmd->add_option("--format", o->format, "text, json, gradescope or prairielearn (their results.json)")
      ->check(CLI::IsMember({"text", "json", "gradescope", "prairielearn"}))
      ->capture_default_str();
  cmd->add_option("--out-dir", o->out_dir, "folder for the wrong rays' viewer state files")->capture_default_str();
  cmd->add_option("--worker", o->worker, "the student's worker program (default: accelviz-worker beside accelviz-cli)");
  cmd->add_option("--submission", o->submission,
                  "a folder of .cpp files: compiled in the sandbox into a worker, then checked");
  return cmd;
}

/// grade-class: check's options (from `check`'s defaults, a shorter timeout) over a class.
CLI::App* add_grade_class_command(CLI::App& app, const cli::CheckOptions& check, cli::GradeClassOptions* o) {
  o->check = check;
  o->check.timeout = 120.0;
  CLI::App* cmd = app.add_subcommand(
      "grade-class", "grade every submission of a class (one subfolder each) in the sandbox: per student a JSON "
                     "report and a CSV row, and one HTML class report (docs/student.md)");
  cmd->add_option("SUBMISSIONS", o->submissions, "folder of submissions, one subfolder per student")->required();
  cmd->add_option("--out", o->out, "folder for the reports (not inside SUBMISSIONS)")->required();
  cmd->add_option("--jobs", o->jobs, "submissions graded at once (0 = one per core)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  cmd->add_flag("--force", o->force, "grade again even the submissions unchanged since their report");
  add_judge_options(cmd, &o->check);
  return cmd;
}

}  // namespace

/// trace, stats, bench and params see a student's structures through their worker (nothing
/// is graded there, so it runs unconfined, as the student's own program): $ACCELVIZ_WORKER,
/// or accelviz-worker beside this program. check and grade-class list their workers
/// themselves, in the sandbox. Before the registry is first used (the options' help texts).
void use_worker_for_queries(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "";
  if (command != "trace" && command != "stats" && command != "bench" && command != "params") return;
  const char* env = std::getenv("ACCELVIZ_WORKER");
  std::string worker = env && *env ? env : "";
  if (worker.empty()) {
    worker = cli::worker_beside_cli();
    if (worker.empty() || access(worker.c_str(), X_OK) != 0) return;
  }
  auto budget = std::make_shared<judge::WorkerBudget>();
  char full[PATH_MAX];
  budget->worker = realpath(worker.c_str(), full) ? full : worker;  // it starts in another folder
  budget->confinement.sandbox = false;
  budget->confinement.allow_processes = true;
  budget->output_limit = SIZE_MAX;
  auto listed = judge::list_worker(budget);
  if (!listed) {
    std::fprintf(stderr, "accelviz-cli: %s: %s (its structures are left out)\n", worker.c_str(),
                 listed.error().message.c_str());
    return;
  }
  accel::set_remote_students(judge::remote_entries(listed.value(), budget));
}

int main(int argc, char** argv) {
  cli::install_interrupt_handlers();
  std::signal(SIGPIPE, SIG_IGN);  // a worker that is gone is an error to report, not the judge's end
  use_worker_for_queries(argc, argv);
  accel::prepare_for_builds();  // before the scene load: its freed memory serves the builds
  CLI::App app{"accelviz-cli: batch ray queries, statistics and benchmarks of acceleration structures"};
  app.require_subcommand(1);
  cli::TraceOptions trace;
  CLI::App* trace_cmd = add_trace_command(app, &trace);
  cli::StatsOptions stats;
  CLI::App* stats_cmd = add_stats_command(app, &stats);
  cli::BenchOptions bench;
  CLI::App* bench_cmd = add_bench_command(app, &bench);
  CLI::App* params_cmd = app.add_subcommand("params", "list the structures and their parameters");
  cli::BuildVsEmbreeOptions build_vs_embree;
  CLI::App* build_vs_embree_cmd = add_build_vs_embree_command(app, &build_vs_embree);
  cli::CheckOptions check;
  CLI::App* check_cmd = add_check_command(app, &check);
  cli::GradeClassOptions grade;
  CLI::App* grade_cmd = add_grade_class_command(app, check, &grade);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, and the exit code every bad input gets.
    std::fprintf(stderr, "accelviz-cli: %s (see --help)\n", e.what());
    return cli::kExitBadInput;
  }
  if (trace_cmd->parsed()) return check_stdout(cli::run_trace(trace));
  if (stats_cmd->parsed()) return check_stdout(cli::run_stats(stats));
  if (bench_cmd->parsed()) return check_stdout(cli::run_bench(bench));
  if (build_vs_embree_cmd->parsed()) return check_stdout(cli::run_build_vs_embree(build_vs_embree));
  if (params_cmd->parsed()) return check_stdout(print_params());
  if (check_cmd->parsed()) return check_stdout(cli::run_check(check));
  if (grade_cmd->parsed()) return check_stdout(cli::run_grade_class(grade));
  return cli::kExitBadInput;
}
