#include "structures/brute_force.h"

namespace accel {

Status BruteForce::build_impl(const Scene& scene, const ParamSet&, BuildControl* control, BuildRecorder* recorder) {
  // Nothing to build: only a cancel that came before the start is honoured.
  scene_ = nullptr;
  stats_ = BuildStats{};
  if (build_cancelled(control)) return cancelled_error();
  scene_ = &scene;
  stats_.nodes = 1;
  stats_.prims = scene.valid_prims().size();
  stats_.prim_references = stats_.prims;
  stats_.add_leaf(stats_.prims);
  if (recorder) {  // the whole construction: one leaf of every triangle
    const std::vector<uint32_t>& prims = scene.valid_prims();
    recorder->scene_box(scene.bounds());
    recorder->node(0, kNoBuildNode, 0, scene.bounds(), Aabb{}, prims.data(), prims.size());
    recorder->leaf(0, LeafReason::FewPrims, prims.data(), prims.size());
    recorder->done(1);
  }
  return {};
}

void BruteForce::for_each_node(const std::function<void(const NodeView&)>& fn) const { fn(node_view(0)); }

NodeView BruteForce::node_view(NodeId id) const {
  NodeView v;
  v.id = id;
  v.leaf = true;
  v.prim_count = uint32_t(scene_ ? scene_->valid_prims().size() : 0);
  if (scene_) v.box = scene_->bounds();
  return v;
}

std::vector<uint32_t> BruteForce::node_prims(NodeId) const {
  return scene_ ? scene_->valid_prims() : std::vector<uint32_t>{};
}

}  // namespace accel
