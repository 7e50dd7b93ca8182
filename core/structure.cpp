#include "structure.h"

#include <chrono>

#include "bit_cast.h"
#include "parallel.h"

namespace accel {

void BuildStats::add_leaf(size_t n) {
  constexpr size_t kBuckets = 17;  // 0..15 triangles, then "16 or more"
  if (leaf_size_histogram.empty()) leaf_size_histogram.assign(kBuckets, 0);
  ++leaves;
  if (n == 0) ++empty_leaves;
  max_leaf_size = std::max(max_leaf_size, n);
  ++leaf_size_histogram[std::min(n, kBuckets - 1)];
}

Status Structure::build(const Scene& scene, const ParamSet& params, BuildControl* control) {
  return timed_build(scene, params, control, nullptr);
}

Status Structure::build_recorded(const Scene& scene, const ParamSet& params, BuildRecorder& recorder,
                                 BuildControl* control) {
  // One thread: the steps come in the order of the serial build (depth first, left before
  // right), and the recorder needs no locks. Builders also take their serial paths when
  // recording, so the arena is only a guarantee.
  par::task_arena one_thread(1);
  Status result;
  one_thread.execute([&] { result = timed_build(scene, params, control, &recorder); });
  return result;
}

Status Structure::timed_build(const Scene& scene, const ParamSet& params, BuildControl* control,
                              BuildRecorder* recorder) {
  const auto start = std::chrono::steady_clock::now();
  report_progress(control, 0.0);
  ParamSet in_use = params;
  in_use.set_planar(scene.planar());  // a 2D scene's defaults where they differ
  auto result = build_impl(scene, in_use, control, recorder);
  if (result) report_progress(control, 1.0);
  build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  refit_ms_ = std::nan("");
  return result;
}

Status Structure::refit(const Scene& scene) {
  const auto start = std::chrono::steady_clock::now();
  auto result = refit_impl(scene);
  if (result) refit_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

Status Structure::refit_impl(const Scene&) {
  return make_error(name() + " cannot refit: rebuild it (only the bounding volume hierarchies keep their topology "
                    "when vertices move)");
}

BuildStats Structure::build_stats() const {
  BuildStats s = compute_stats();
  s.build_ms = build_ms_;
  s.refit_ms = refit_ms_;
  return s;
}

uint64_t structure_digest(const Structure& structure) {
  uint64_t h = 0xcbf29ce484222325ull;
  const auto mix = [&h](const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  };
  const auto mix_value = [&mix](auto v) { mix(&v, sizeof v); };
  structure.for_each_node([&](const NodeView& n) {
    mix_value(n.id);
    mix_value(int32_t(n.depth));
    mix_value(uint8_t(n.leaf));
    mix_value(n.prim_count);
    for (int k = 0; k < 3; ++k) {
      mix_value(bit_cast<uint32_t>(n.box.min[k]));
      mix_value(bit_cast<uint32_t>(n.box.max[k]));
      mix_value(bit_cast<uint32_t>(n.sphere.center[k]));
    }
    mix_value(bit_cast<uint32_t>(n.sphere.radius));
    mix_value(int32_t(n.split_axis));
    mix_value(bit_cast<uint32_t>(n.split_pos));
    for (NodeId child : structure.node_children(n.id)) mix_value(child);
    if (n.leaf)
      for (uint32_t prim : structure.node_prims(n.id)) mix_value(prim);
  });
  return h;
}

}  // namespace accel
