#pragma once
// The partly built structure as of a construction step: applies the recorded steps of a
// BuildTrace (build_trace.h) in order and keeps what exists after them -- the nodes created
// so far with their boxes, triangles and children, the grid's cells. The viewer draws it,
// the tests check that after the last step it is the structure the build produced.
// Nothing here re-runs a builder: every number comes from the recorded events.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "build_trace.h"

namespace accel {

/// One node as of the current step.
struct ReplayNode {
  uint32_t id = kNoBuildNode;      ///< the builder's id (the events' node)
  uint32_t parent = kNoBuildNode;  ///< slot of the parent (kNoBuildNode: a root or a loose cluster)
  int depth = 0;                   ///< as recorded (bottom-up clusters: 0 until depths() is asked)
  Aabb box;                        ///< latest box: the node's, grown by insertion, or its final fit
  BoundingSphere sphere;           ///< the sphere tree's fitted sphere (radius < 0 otherwise)
  Aabb centroids;                  ///< centroid bounds when recorded
  std::vector<uint32_t> prims;     ///< its triangles (a leaf's own, an inner node's when recorded)
  std::vector<uint32_t> children;  ///< child slots, in the builder's order
  uint32_t prim_count = 0;
  int split_axis = -1;             ///< after its Split: the axis (3 = PCA) and plane
  float split_pos = 0.0f;
  bool leaf = false;
  bool unrecorded = false;         ///< built below the recorded depth (drawn, not expanded)
  bool gone = false;               ///< removed: collapsed into its parent, or below a leaf
};

/// The grid's state: resolution and the cells filled so far.
struct ReplayGrid {
  bool resolved = false;
  Aabb box;
  int res[3] = {0, 0, 0};
  std::vector<std::vector<uint32_t>> cells;  ///< by linear cell index (x fastest)
};

class BuildReplay {
 public:
  explicit BuildReplay(const BuildTrace& trace) : trace_(&trace) { reset(); }

  size_t steps() const { return trace_->events.size(); }
  /// Steps applied so far (0 = nothing built yet; steps() = the finished build).
  size_t step() const { return applied_; }
  /// Moves to the state after `k` steps (clamped); going back replays from the start.
  void seek(size_t k);
  /// The last applied step (nullptr before the first).
  const BuildEvent* current() const { return applied_ ? &trace_->events[applied_ - 1] : nullptr; }

  const std::vector<ReplayNode>& nodes() const { return nodes_; }
  /// The slot of builder node `id`, kNoBuildNode if it does not exist (yet).
  uint32_t slot(uint32_t id) const { return id < slot_of_.size() ? slot_of_[id] : kNoBuildNode; }
  /// Depths from the parent links (what a node's depth is once bottom-up merges or wide
  /// collapses moved it): depth of every slot, -1 for gone nodes.
  std::vector<int> depths() const;
  const ReplayGrid& grid() const { return grid_; }
  const Aabb& scene_box() const { return scene_box_; }
  /// Counters as of the current step.
  size_t live_nodes() const { return live_nodes_; }
  size_t leaves() const { return leaves_; }
  size_t references() const { return references_; }
  /// The SAH cost of the tree as it stands (the lecture's C(T), normalised to the root's
  /// area): ct per inner node and ci per `prims_per_test` triangles of a leaf (rounded up;
  /// BuildStats::sah_prims_per_test: 4 for the wide layouts), weighted by area / root area,
  /// with the nodes not yet split counted as leaves -- it falls as the build advances and
  /// ends at the finished tree's cost (for boxes; spheres use their area). NaN for a grid.
  double sah_cost(double ct, double ci, int prims_per_test = 1) const;

 private:
  void reset();
  void apply(const BuildEvent& e);
  uint32_t create(uint32_t id);
  void remove_subtree(uint32_t slot);
  // apply()'s steps that change the tree or the grid, one per kind of event.
  void apply_grid_resolution(const BuildEvent& e);
  void apply_grid_insert(const BuildEvent& e);
  void apply_node(const BuildEvent& e);
  void apply_leaf(const BuildEvent& e, uint32_t s);
  void apply_merge(const BuildEvent& e);
  void apply_collapse(const BuildEvent& e, uint32_t s);
  void apply_replace(const BuildEvent& e, uint32_t s);

  const BuildTrace* trace_;
  size_t applied_ = 0;
  std::vector<ReplayNode> nodes_;
  std::vector<uint32_t> slot_of_;
  ReplayGrid grid_;
  Aabb scene_box_;
  size_t live_nodes_ = 0, leaves_ = 0, references_ = 0;
};

}  // namespace accel
