#pragma once
// The kit's own reading of a student's traversal: every claim of the traversal log checked
// against the geometry -- the tree the build log described, the ray, the exact (double)
// triangle tests -- and never against the student's own flags. Used by the grader (the cause
// of each wrong answer, what a right structure wastes) and by the viewer (a step whose claim
// is false is marked so, with the true values beside it, instead of being repeated).
//
// Two kinds of false claims:
//   lossy  the claim dropped part of the ray's path that holds a nearer hit (a node skipped
//          as missed or as beyond the closest hit, a kd-tree case that leaves out a child the
//          ray crosses, an early exit before the far child, a grid walk that leaves the ray);
//          the first one on a wrong ray is its diagnosis, named in the lecture's words;
//   waste  the claim costs time only (a node visited over an interval in which the ray does
//          not cross it: case (c) missing); counted for the inefficiency report.
// When no claim is lossy, the answer itself is read: a returned triangle that is not hit, a
// nearer triangle tested and dropped, a triangle lost at a split, a leaf never reached.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "accelviz_student.h"
#include "accuracy.h"
#include "scene.h"
#include "trace.h"

namespace accel {

struct KitTree;

/// One cause of wrong answers: what groups them in check's report.
struct CauseInfo {
  const char* id;       ///< stable key: "kd_plane_behind_origin", ... (--json's "cause")
  const char* title;    ///< the lecture's words: the same text in the report and docs/student.md
  const char* lecture;  ///< where the lecture (or its fix) says it
};
/// Every cause check can name, in the order docs/student.md lists them.
std::span<const CauseInfo> cause_table();
/// The cause `id`; the "unexplained" cause for an unknown id.
const CauseInfo& cause_info(const std::string& id);

/// One logged claim the geometry contradicts.
struct FalseClaim {
  size_t step = 0;         ///< the event index it belongs to (the viewer marks that step)
  std::string cause;       ///< a cause_table() id
  std::string claim;       ///< what the log said ("t_hit 2.5566 < t_split 1.5883: return")
  std::string truth;       ///< what is true ("the far child is entered at t=1.5883, before the hit")
  bool loses_hit = false;  ///< lossy: a nearer hit lies in what the claim dropped
};

/// What the kit read from one traversal.
struct WalkAudit {
  std::vector<FalseClaim> claims;  ///< in step order, at most kMaxClaims
  static constexpr size_t kMaxClaims = 64;
  size_t visits = 0;               ///< Visit / EnterCell events
  size_t visits_not_crossed = 0;   ///< of those, over an interval where the ray misses the node
  size_t kd_inner = 0;             ///< kd_split records
  size_t kd_far_only = 0;          ///< of those, case (c)
  size_t kd_needs_far_only = 0;    ///< of those, nodes where the ray crosses only the far child
  /// The first lossy claim, or null.
  const FalseClaim* first_lossy() const;
  /// The claim at `step`, or null.
  const FalseClaim* at(size_t step) const;
};

/// The cause of one wrong answer, with the sentence that explains it for this ray.
struct Diagnosis {
  std::string cause;   ///< a cause_table() id
  std::string detail;  ///< this ray's numbers: "node 5: t_split=-0.83 < 0, ..."
  size_t step = size_t(-1);  ///< the step it happened at (the viewer's), or -1
};

/// Reads student traversals over one built tree and scene. Holds per-scene indexes (which
/// leaves and cells hold each triangle), made on first use.
class WalkAuditor {
 public:
  WalkAuditor(const KitTree& tree, accelviz::Kind kind, const Scene& scene);
  ~WalkAuditor();
  WalkAuditor(const WalkAuditor&) = delete;
  WalkAuditor& operator=(const WalkAuditor&) = delete;

  /// Checks every claim of one recorded traversal of `ray`. `find_lossy`: also decide which
  /// false claims drop a nearer hit (brute force over the scene's triangles: the wrong rays
  /// and the viewer's one ray, not every ray of a check).
  WalkAudit audit(const Ray& ray, std::span<const TraceEvent> events, std::span<const RecordedVars> vars,
                  bool find_lossy) const;
  /// The cause of a wrong answer `got` (the reference: `ref`), from its audit and its walk.
  Diagnosis diagnose(const Ray& ray, std::span<const TraceEvent> events, std::span<const RecordedVars> vars,
                     const WalkAudit& audit, const Hit& got, const ReferenceHit& ref) const;

 private:
  struct Index;
  const Index& index() const;

  const KitTree& tree_;
  accelviz::Kind kind_;
  const Scene& scene_;
  mutable std::unique_ptr<Index> index_;
};

}  // namespace accel
