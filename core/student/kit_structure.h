#pragma once
// A student's structure (student/accelviz_student.h) as one of the core's: the adapter that
// lets the CLI, the viewer, the benchmark and the checks treat it like a built-in one.
//
// The student writes build() and intersect() and calls the two logs; nothing else. The
// adapter always listens to the build log and keeps from it what the front ends ask a
// structure for (node_view, node_prims, node_children, the statistics), so a student writes
// no node-query or drawing code. The traversal log is listened to only when the caller
// counts or records (intersect with stats, intersect_traced): a batch query passes a log
// with no listener, and each of the student's log calls is then one untaken branch.
#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "accelviz_student.h"
#include "structure.h"

namespace accel {

/// A student's bug that the kit detected while running its code: an out-of-range triangle
/// returned, the step budget of one query exceeded (an endless loop), a log call naming a
/// node never made. Thrown only when KitStructure::set_strict(true) (the grader).
class KitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Thrown by the kit's build listener when a replay's build-log call limit is reached
/// (KitStructure::set_build_call_limit): the build ends there, keeping what it logged.
class KitBuildStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The student's code stopped answering for good: its worker process crashed, exited, ran
/// past the time limit, printed past the output limit or broke the wire. Thrown by a
/// RemoteAnswers object (the judge's proxy of a worker); the grader ends the structure's
/// check with it, keeping what it had judged so far. what() says what happened ("crashed
/// (Segmentation fault)"), hint() what may cause it.
class StudentProcessLost : public std::runtime_error {
 public:
  StudentProcessLost(const std::string& what, std::string hint = "")
      : std::runtime_error(what), hint_(std::move(hint)) {}
  const std::string& hint() const { return hint_; }

 private:
  std::string hint_;
};

/// A student object whose code runs elsewhere (the judge's proxy of a worker process, in
/// app/cli/judge/): it can be given a case's rays ahead, so they travel in one request, and
/// it times a batch of rays in the worker.
class RemoteAnswers {
 public:
  virtual ~RemoteAnswers() = default;
  /// The next calls of intersect() will be these rays in this order, each listened to
  /// (modes & 1) and then on the fast path (modes & 2), as the grader asks.
  virtual void expect(const std::vector<Ray>& rays, Kernel kernel, uint8_t modes) = 0;
  /// The wall seconds the worker took to answer every ray on the fast path on `threads`
  /// threads (the request sent, the answers received), and its answers.
  virtual double time_rays(const std::vector<Ray>& rays, Kernel kernel, unsigned threads,
                           std::vector<Hit>* answers) = 0;
};

/// One node (or leaf) as the student's build log described it.
struct KitNode {
  uint32_t student_id = kNoBuildNode;
  uint32_t parent = kNoBuildNode;  ///< dense id of the parent
  int depth = 0;
  Aabb box;
  BoundingSphere sphere;
  uint32_t prim_count = 0;          ///< triangles the node was made over
  std::vector<uint32_t> prims;      ///< a leaf's triangles
  std::vector<uint32_t> made_over;  ///< the triangles node() named (kept for the checks only)
  std::vector<uint32_t> children;   ///< dense ids, in the order they were made
  int split_axis = -1;
  float split_pos = 0.0f;
  bool leaf = false;
  accelviz::LeafWhy leaf_why = accelviz::LeafWhy::FewTriangles;
};

/// What the student's build log said, with the students' ids made dense (0, 1, ... in the
/// order node() was called): the structure the viewer draws and the checks inspect.
struct KitTree {
  std::vector<KitNode> nodes;
  std::unordered_map<uint32_t, uint32_t> dense_of;  ///< student id -> dense id
  bool keep_made_over = false;                      ///< keep every node's triangles (strict: the grader's invariants)
  bool grid = false;
  Aabb grid_box;
  int res[3] = {0, 0, 0};
  std::vector<std::vector<uint32_t>> cells;  ///< by linear cell index, x fastest
  /// Calls the log could not make sense of (first few), e.g. "leaf(7): node 7 was never made".
  std::vector<std::string> problems;
  size_t problem_count = 0;
  size_t log_calls = 0;  ///< build-log calls heard (a failed build's replay stops after as many)

  uint32_t dense(uint32_t student_id) const {
    auto it = dense_of.find(student_id);
    return it == dense_of.end() ? kNoBuildNode : it->second;
  }
  size_t cell_count() const { return size_t(res[0]) * size_t(res[1]) * size_t(res[2]); }
  /// Linear index of cell (x, y, z), or kNoNode outside the grid.
  NodeId cell_index(int x, int y, int z) const;
  Aabb cell_box(NodeId cell) const;
  void problem(std::string what);
};

/// Budget of one traversal's logged steps before the kit calls it endless (strict mode).
inline constexpr uint64_t kKitStepBudget = 20'000'000;

/// Makes the student's object: the registration's constructor where the student's code is
/// linked in (the viewer), or a RemoteStudent that talks to a worker process (the judge).
using StudentFactory = std::function<std::unique_ptr<accelviz::StudentStructure>()>;

class KitStructure final : public Structure {
 public:
  KitStructure(std::string name, accelviz::Kind kind, StudentFactory create);

  std::string name() const override { return name_; }
  Hit intersect(const Ray& ray, QueryStats* stats = nullptr) const override;
  Hit intersect_traced(const Ray& ray, TraceRecorder& recorder) const override;
  void for_each_node(const std::function<void(const NodeView&)>& fn) const override;
  NodeView node_view(NodeId id) const override;
  std::vector<uint32_t> node_prims(NodeId id) const override;
  std::vector<NodeId> node_children(NodeId id) const override;

  /// Strict (the grader): the student's exceptions and the kit's KitErrors propagate out
  /// of build() and the queries. Otherwise (the viewer, the CLI) a throwing build is an
  /// Error naming the structure, and a throwing query is a miss whose message is kept in
  /// last_error().
  void set_strict(bool strict) { strict_ = strict; }
  /// The last message of a query that threw (non-strict), "" if none.
  std::string last_error() const;
  const KitTree& tree() const { return tree_; }
  accelviz::Kind kind() const { return kind_; }
  /// The student's answer to `ray` with the log listened to by `listener` (null: nobody),
  /// through the same call as intersect(); strict errors as above.
  Hit run_query(const Ray& ray, accelviz::detail::TraversalListener* listener) const;
  /// The student's object of the last build (null before one): the grader asks a remote one
  /// for batches and timings.
  accelviz::StudentStructure* student() const { return student_.get(); }
  /// Triangles of the scene of the last build (0 before one): an answer's valid range.
  size_t scene_triangles() const { return scene_ ? scene_->triangle_count() : 0; }
  /// Build-log calls of the last build, whole or failed.
  size_t build_log_calls() const { return tree_.log_calls; }
  /// The viewer's replay of a failed build: stop the student's build right after its
  /// `calls`-th build-log call (0: never), as if it had failed there, keeping what was logged
  /// for playback; the build then returns an Error saying so.
  void set_build_call_limit(size_t calls) { build_call_limit_ = calls; }
  /// The last build stopped at that limit (its Error is the stop, not a fault of its own): the
  /// tree holds what was logged up to there, and no student object answers queries.
  bool build_stopped() const { return build_stopped_; }

 protected:
  Status build_impl(const Scene& scene, const ParamSet& params, BuildControl* control,
                    BuildRecorder* recorder) override;
  BuildStats compute_stats() const override;

 private:
  Hit guarded_query(const Ray& ray, accelviz::detail::TraversalListener* listener) const;

  std::string name_;
  accelviz::Kind kind_;
  StudentFactory create_;
  std::unique_ptr<accelviz::StudentStructure> student_;
  std::unique_ptr<accelviz::Scene> student_scene_;
  const Scene* scene_ = nullptr;
  KitTree tree_;
  bool strict_ = false;
  size_t build_call_limit_ = 0;
  bool build_stopped_ = false;
  mutable std::mutex error_mutex_;
  mutable std::string last_error_;
};

}  // namespace accel
