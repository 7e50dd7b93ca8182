// The BVH builders' front door: build_bvh_tree() runs the builder the options name, each in
// its own file after the lecture's algorithm --
//   top-down   bvh_median_builder.cpp (median split), bvh_sweep_builder.cpp (SAH plane
//              sweep on all axes), bvh_pca_builder.cpp (SAH sweep along the PCA axis), all
//              three over bvh_top_down.h's recursion; bvh_binned_builder.cpp (binned SAH,
//              the default) and bvh_spatial_builder.cpp (SBVH) with their own;
//   bottom-up  bvh_ploc_builder.cpp (clustering), bvh_insertion_builder.cpp (Goldsmith &
//              Salmon), both finished by bvh_binary_tree.cpp.
#include "structures/bvh_builders.h"

#include "check.h"

#include "structures/bvh_binned_builder.h"
#include "structures/bvh_insertion_builder.h"
#include "structures/bvh_median_builder.h"
#include "structures/bvh_pca_builder.h"
#include "structures/bvh_ploc_builder.h"
#include "structures/bvh_spatial_builder.h"
#include "structures/bvh_sweep_builder.h"

namespace accel {

const char* builder_name(BvhBuilderKind kind) {
  switch (kind) {
    case BvhBuilderKind::Median: return "median";
    case BvhBuilderKind::Sah: return "sah";
    case BvhBuilderKind::BinnedSah: return "binned_sah";
    case BvhBuilderKind::PcaSah: return "pca_sah";
    case BvhBuilderKind::BottomUp: return "bottom_up";
    case BvhBuilderKind::Insertion: return "insertion";
    case BvhBuilderKind::Sbvh: return "sbvh";
  }
  return "?";
}

Status check_bvh_memory(const std::string& structure, const Scene& scene, const BvhBuildOptions& options,
                        size_t layout_bytes_per_node, size_t memory_limit) {
  const size_t triangles = scene.valid_prims().size();
  const bool spatial = options.builder == BvhBuilderKind::Sbvh;
  const double refs = double(triangles) * (spatial ? double(options.sbvh_budget) : 1.0);
  // Per reference: two builder nodes and one index in BuildTree, two layout nodes and the
  // layout's index, and the builders' scratch (centroids, boxes, bin counts, sort keys),
  // measured at under 96 bytes per triangle for every builder on the 10M-triangle scene.
  constexpr double kScratchPerReference = 96.0;
  const double per_ref = 2.0 * double(sizeof(BuildNode) + layout_bytes_per_node) + 2.0 * sizeof(uint32_t) +
                         kScratchPerReference;
  const double need = refs * per_ref;
  if (need <= double(memory_limit)) return {};
  return make_error(structure + ": " + std::to_string(triangles) + " triangles with builder=" +
                    builder_name(options.builder) + " " + over_budget_text(need, memory_limit) +
                    (spatial && options.sbvh_budget > 1.0f ? "; lower sbvh_budget" : "; raise the memory limit"));
}

// Every builder numbers a node before its children, so one reverse pass suffices.
std::vector<uint32_t> binary_subtree_sizes(const BuildTree& tree) {
  std::vector<uint32_t> size(tree.nodes.size(), 1);
  for (size_t i = tree.nodes.size(); i-- > 0;) {
    const BuildNode& n = tree.nodes[i];
    if (n.count) continue;
    ACCEL_CHECK(n.left > i && n.right > i);
    size[i] += size[n.left] + size[n.right];
  }
  return size;
}

BuildTree build_bvh_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                         BuildRecorder* recorder) {
  switch (options.builder) {
    case BvhBuilderKind::Median: return build_median_tree(scene, options, progress, recorder);
    case BvhBuilderKind::Sah: return build_sweep_tree(scene, options, progress, recorder);
    case BvhBuilderKind::BinnedSah: return build_binned_sah_tree(scene, options, progress, recorder);
    case BvhBuilderKind::PcaSah: return build_pca_tree(scene, options, progress, recorder);
    case BvhBuilderKind::BottomUp: return build_ploc_tree(scene, options, progress, recorder);
    case BvhBuilderKind::Insertion: return build_insertion_tree(scene, options, progress, recorder);
    case BvhBuilderKind::Sbvh: return build_spatial_split_tree(scene, options, progress, recorder);
  }
  return {};
}

}  // namespace accel
