#pragma once
// The assignment kit's grader (`accelviz-cli check`): runs a student structure over the
// correctness suites, judges every answer against the double-precision reference by the
// docs/hits.md rule, names the lecture's traps behind wrong answers, checks invariants from
// the build and traversal logs, and times the structure against the built-in one of its
// kind. GL-free. In the judge (`accelviz-cli check`) the structure's student object is a
// proxy of a worker process (app/cli/judge/): the student's code runs there, in a sandbox,
// and a crash, an endless loop or a flood of output ends that structure's check with the
// case and the ray it happened on (CheckReport::failure), never the judge.
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "accuracy.h"
#include "registry.h"
#include "student/waste.h"

namespace accel {

struct CheckOptions {
  std::string shared_scenes;  ///< ../shared/scenes ("" or missing: the meshes category is skipped)
  double ray_scale = 1.0;     ///< ray counts multiplied by this (tests use less)
  size_t examples_per_cause = 2;  ///< wrong rays kept per cause, with the details and replay files
  bool time = true;               ///< measure speed against the built-in structure (a passing structure only)
  /// --strict: fail a right structure whose waste passes a limit (WasteLimits).
  bool strict = false;
  WasteLimits limits;
  /// Called before the timing starts: the judge gives the timing its own time limit.
  std::function<void()> before_timing;
  /// Held while timing, when several checks run at once (grade-class): two timings never
  /// share the cores.
  std::mutex* timing_mutex = nullptr;
};

/// Rays tried and wrong answers by kind, per suite category.
struct CheckCategory {
  std::string name;  ///< "procedural", "edge", "hard", "meshes"
  size_t cases = 0, rays = 0;
  size_t wrong[5] = {0, 0, 0, 0, 0};  ///< by HitVerdict (Correct unused)
  size_t skipped_cases = 0, skipped_rays = 0;  ///< not run after faults (rays counted, never judged)
  size_t wrong_total() const { return wrong[1] + wrong[2] + wrong[3] + wrong[4]; }
};

/// One wrong answer, kept for its report and replay.
struct WrongRay {
  std::string category, case_name;
  std::shared_ptr<const Scene> scene;
  size_t index = 0;  ///< the ray's index within its case
  Ray ray;
  HitVerdict verdict = HitVerdict::Correct;
  Hit got;
  ReferenceHit ref;
  std::string cause;   ///< its cause (walk_audit.h's cause_table id)
  std::string detail;  ///< the cause, with this ray's numbers
  size_t step = size_t(-1);  ///< the traversal step it happened at (the replay opens there), -1: none
};

/// A build that failed (threw, crashed, ran out of memory or time): what the replay needs.
struct BuildFault {
  std::string category, case_name;
  std::shared_ptr<const Scene> scene;
  std::string what;       ///< "build threw: std::bad_alloc"
  std::string node;       ///< the node being built: its depth, triangles, and their growth
  size_t log_calls = 0;   ///< build-log calls made before the fault: the replay stops there
};

/// The wrong rays of one cause.
struct CheckCause {
  std::string id;  ///< cause_table() id
  size_t rays = 0;
  std::vector<std::pair<std::string, size_t>> cases;  ///< "hard/slivers" -> wrong rays of this cause, most first
  std::vector<WrongRay> examples;                     ///< from the cases with the most, one per case first
};

/// One case's counts.
struct CheckCase {
  std::string category, name;
  size_t rays = 0, wrong = 0, skipped = 0;
};

/// One invariant of the logs, over every case.
struct CheckInvariant {
  std::string name;
  bool applies = true;  ///< false: the structure's kind does not promise it
  size_t checked = 0, failed = 0;
  std::string first_failure;
};

struct CheckSpeed {
  bool timed = false;
  std::string why_not;  ///< why there is no timing
  std::string workload;
  double mrays = 0, peer_mrays = 0;
  double nodes = 0, peer_nodes = 0;  ///< per ray
  double tris = 0, peer_tris = 0;    ///< per ray
};

struct CheckReport {
  std::string structure, kind, peer, source_file;
  std::vector<CheckCategory> categories;
  std::vector<CheckCase> cases;
  std::vector<CheckCause> causes;  ///< every wrong ray's cause, the most rays first
  std::vector<std::string> notices;  ///< what the check left out and why ("meshes: skipped: ...")
  WasteReport waste;                 ///< what a right structure wastes against its built-in
  std::vector<CheckInvariant> invariants;
  CheckSpeed speed;
  std::vector<std::string> faults;  ///< exceptions and kit errors, "where: what"
  std::vector<BuildFault> build_faults;
  /// Why the check stopped early ("crashed (Segmentation fault) at hard/slivers ray 12"),
  /// "" when it ran to the end; what was judged before is kept.
  std::string failure;
  size_t rays() const;
  size_t wrong() const;
  size_t invariant_failures() const;
  /// Every example ray, cause by cause.
  std::vector<const WrongRay*> examples() const;
  /// Every answer right, every invariant kept, nothing thrown, nothing stopped (and, with
  /// --strict, no waste past a limit).
  bool passed() const {
    return wrong() == 0 && invariant_failures() == 0 && faults.empty() && failure.empty() && !waste.over_limit;
  }
};

/// Called before each case ("hard/slivers") and every ray (its index): where the child
/// process is, for the report when it crashes or hangs.
using CheckProgress = std::function<void(const std::string& where, size_t ray)>;

/// Checks `info` (a student structure). Exceptions escape only from what the grader cannot
/// attribute (none in practice); the student's exceptions become faults.
CheckReport check_structure(const StructureInfo& info, const CheckOptions& options, const CheckProgress& progress);

/// Writes `scene` as an OBJ whose floats read back exactly (%.9g): the replay's scene.
Status write_scene_obj(const Scene& scene, const std::string& path);

}  // namespace accel
