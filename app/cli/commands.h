#pragma once
// The subcommands of accelviz-cli. Each returns the process exit code: 0 on success,
// 2 on bad input (with a one-line message on stderr), never a partial output file.
#include <string>
#include <vector>

#include "build_control.h"

namespace cli {

/// Options shared by the subcommands that build a structure.
struct StructureOptions {
  std::string scene;
  std::string structure = "brute";
  std::vector<std::string> params;
  std::string kernel = "watertight";
  /// The build's memory budget ("4G", "512M", "25%"; empty: memory_budget.h's default).
  std::string memory_limit;
  /// Seconds a build may take before it stops with an error (0: no limit).
  double time_limit = 0.0;
};

struct TraceOptions {
  StructureOptions build;
  std::string rays;
  std::string out;
  int threads = 0;
};

struct StatsOptions {
  StructureOptions build;
  bool json = false;
  std::string rays;   ///< optional: also trace these rays and report per-ray counters
  int threads = 0;
  std::string build_trace;       ///< optional: also record the construction steps to this JSON-lines file
  int build_trace_budget_mb = 512;  ///< memory for the recorded steps (deeper levels are dropped beyond it)
  bool digest = false;  ///< also print structure_digest() of the tree as built (before any refit)
};

struct BenchOptions {
  std::vector<std::string> scenes;
  std::string structures = "all";   ///< comma list, or "all" (every structure but brute)
  std::vector<std::string> params;  ///< key=value (to every structure that has the key) or structure:key=value
  std::string rays = "primary:1024:1024";
  int threads = 0;
  std::string kernels = "watertight";
  std::string out_md, out_csv, out_json;
  bool embree = true;
  bool embree_robust = false;  ///< also an embree-robust row (RTC_SCENE_FLAG_ROBUST, medium quality)
  bool tinybvh = true;    ///< the tinybvh peer rows (when built with tinybvh and the CPU has AVX2)
  double min_time = 0.5;  ///< seconds each timing sample lasts at least
  std::string memory_limit;  ///< as StructureOptions
  double time_limit = 0.0;   ///< as StructureOptions, per build
};

/// accelviz-cli build-vs-embree: the default BVH's cold build against Embree medium's
/// (build_vs_embree.cpp), each the first build of a fresh child process.
struct BuildVsEmbreeOptions {
  std::vector<std::string> scenes;
  int runs = 3;     ///< child processes per side and scene; the median is kept
  int threads = 0;  ///< build threads of both sides (0 = all cores)
  std::string out_json, out_md;
  std::string child;  ///< hidden: "accelviz" or "embree" makes this process one child
};

/// accelviz-cli check: the assignment kit's grader (check_command.cpp, docs/student.md).
struct CheckOptions {
  std::string structure;      ///< one student structure; empty: every one the worker holds
  bool json = false;          ///< --json: the same as --format json
  std::string format = "text";  ///< text, json, gradescope, prairielearn
  std::string out_dir = "accelviz-check";  ///< replay files of the wrong rays
  std::string shared;         ///< ../shared/scenes for the meshes category
  double ray_scale = 1.0;
  bool time = true;
  bool strict = false;        ///< --strict: waste past a limit fails
  std::vector<std::string> limits;  ///< --limit NAME=VALUE
  double timeout = 300.0;     ///< seconds per structure before its worker is stopped (the timing has its own)
  std::string memory_limit;   ///< per structure's worker (default: 4 GiB or half the memory)
  size_t memory_bytes = 0;
  std::string worker;         ///< the worker program (default: accelviz-worker beside accelviz-cli)
  std::string submission;     ///< a folder of .cpp files to compile into a worker first
  bool sandbox = true;        ///< false: --no-sandbox
};

/// accelviz-cli grade-class: every submission of a class (grade_class.cpp, docs/student.md).
struct GradeClassOptions {
  std::string submissions;  ///< one subfolder per student
  std::string out;          ///< reports, CSV, HTML
  int jobs = 0;             ///< submissions graded at once (0: one per core)
  bool force = false;       ///< grade again even when unchanged
  CheckOptions check;       ///< the options every submission is checked with
};

int run_trace(const TraceOptions& options);
int run_check(const CheckOptions& options);
int run_grade_class(const GradeClassOptions& options);
int run_bench(const BenchOptions& options);
int run_build_vs_embree(const BuildVsEmbreeOptions& options);
int run_stats(const StatsOptions& options);

/// Sets the control's memory and time limits from the options' text; the error names
/// --memory-limit.
accel::Status apply_build_limits(const std::string& memory_limit, double time_limit, accel::BuildControl* control);
/// A build's error as the CLI prints it: a build stopped by the time limit says so.
accel::Error build_error(const accel::Error& error, const std::string& structure, const accel::BuildControl& control);

/// Exit code for bad input.
inline constexpr int kExitBadInput = 2;

}  // namespace cli
