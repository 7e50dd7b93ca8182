// The BVH builders' front door: build_bvh_tree() runs the builder the options name, each in
// its own file after the lecture's algorithm --
//   top-down   bvh_median_builder.cpp (median split), bvh_sweep_builder.cpp (SAH plane
//              sweep on all axes), bvh_pca_builder.cpp (SAH sweep along the PCA axis),
//              bvh_binned_builder.cpp (binned SAH, the default) and bvh_spatial_builder.cpp
//              (SBVH): each a splitter of the one recursion, bvh_top_down.h;
//   bottom-up  bvh_ploc_builder.cpp (clustering), bvh_insertion_builder.cpp (Goldsmith &
//              Salmon), both finished by bvh_binary_tree.cpp;
// and the table that names them (bvh_builders.h).
#include "structures/bvh_builders.h"

#include <atomic>
#include <iterator>
#include <limits>
#include <type_traits>
#include <vector>

#include "check.h"

#include "structures/bvh_binned_builder.h"
#include "structures/bvh_insertion_builder.h"
#include "structures/bvh_median_builder.h"
#include "structures/bvh_pca_builder.h"
#include "structures/bvh_ploc_builder.h"
#include "structures/bvh_spatial_builder.h"
#include "structures/bvh_sweep_builder.h"

namespace accel {

// The builders' construction listings (BvhBuilderInfo::listing), after the lecture's slides.
constexpr ListingLine kMedianLines[] = {
    {"axis", "    axis: x / cycle x,y,z / longest extent"},
    {"", "    sort the objects by their centre along it"},
    {"split", "    split at the median: half left, half right"},
};
constexpr BuilderListing kMedianListing{"BVH: top-down, median (lecture)", kMedianLines};

constexpr ListingLine kSweepLines[] = {
    {"axis", "    for each axis x, y, z:"},
    {"candidates", "        sweep: C(B) at every position"},
    {"split", "    split at the minimum of C(B),"},
    {"", "        unless the leaf is cheaper"},
};
constexpr BuilderListing kSweepListing{"BVH: top-down, SAH plane sweep", kSweepLines};

constexpr ListingLine kBinnedLines[] = {
    {"axis", "    for each axis x, y, z:"},
    {"candidates", "        bin the centres; C(B) at each bin boundary"},
    {"split", "    split at the minimum of C(B),"},
    {"", "        unless the leaf is cheaper"},
};
constexpr BuilderListing kBinnedListing{"BVH: top-down, binned SAH", kBinnedLines};

constexpr ListingLine kPcaLines[] = {
    {"", "    represent all polygons by their midpoints"},
    {"axis", "    axis of largest extent (using PCA)"},
    {"", "    project the midpoints onto it and sort"},
    {"candidates", "    search minimum of C(B) by plane sweep"},
    {"split", "    split there, unless the leaf is cheaper"},
};
constexpr BuilderListing kPcaListing{"BVH: top-down, PCA + SAH (lecture)", kPcaLines};

constexpr ListingLine kBottomUpLines[] = {
    {"scene_box", "elementary BVs around all objects"},
    {"node", "each object is a cluster (a leaf)"},
    {"leaf", "    leaf of one triangle"},
    {"", "while more than one cluster:"},
    {"merge", "    combine the two whose BV is smallest"},
    {"", "    enclose them in a (larger) BV"},
};
constexpr BuilderListing kBottomUpListing{"BVH: bottom-up (lecture)", kBottomUpLines};

constexpr ListingLine kInsertionLines[] = {
    {"scene_box", "start with an empty tree"},
    {"", "for each polygon:   [Goldsmith/Salmon]"},
    {"insert_step", "    sift: here, left or right (least cost)"},
    {"node", "    new leaf (sibling where it stopped)"},
    {"leaf", "    leaf of the polygon"},
    {"merge", "    new inner node over it and that sibling"},
};
constexpr BuilderListing kInsertionListing{"BVH: iterative insert (lecture)", kInsertionLines};

constexpr ListingLine kSpatialLines[] = {
    {"axis", "    for each axis x, y, z:"},
    {"candidates", "        object split: bin the centres, C(B) per boundary;"},
    {"", "        if the two boxes overlap: spatial split: cut the"},
    {"", "        node's box into bins, clip each triangle into the"},
    {"", "        bins it crosses, C(B) per bin boundary"},
    {"split", "    split at the cheaper minimum (spatial: triangles"},
    {"", "        on both sides go to both, with clipped boxes),"},
    {"", "        unless the leaf is cheaper"},
};
constexpr BuilderListing kSpatialListing{"BVH: top-down, spatial splits (Stich et al. 2009)", kSpatialLines};

// The table: the one place a builder is named. Its order is the parameter's.
constexpr BvhBuilderInfo kBuilders[] = {
    {BvhBuilderKind::Median, "median", "median", "top-down median split", false, true, &kMedianListing,
     build_median_tree},
    {BvhBuilderKind::Sah, "sah", "SAH sweep", "SAH plane sweep on all axes", false, true, &kSweepListing,
     build_sweep_tree},
    {BvhBuilderKind::BinnedSah, "binned_sah", "binned SAH", "binned SAH", false, true, &kBinnedListing,
     build_binned_sah_tree},
    {BvhBuilderKind::PcaSah, "pca_sah", "PCA + SAH", "SAH sweep along the PCA axis", false, true, &kPcaListing,
     build_pca_tree},
    {BvhBuilderKind::BottomUp, "bottom_up", "bottom-up", "bottom-up agglomerative clustering", false, false,
     &kBottomUpListing, build_ploc_tree},
    {BvhBuilderKind::Insertion, "insertion", "insertion", "Goldsmith-Salmon insertion", false, false,
     &kInsertionListing, build_insertion_tree},
    {BvhBuilderKind::Sbvh, "sbvh", "spatial splits",
     "binned SAH with spatial splits (SBVH: a triangle may be in several leaves)", true, true, &kSpatialListing,
     build_spatial_split_tree},
};

namespace {

/// kBuilders and the rows add_bvh_builder() appended; `read` once anyone has looked.
struct BuilderRows {
  std::vector<BvhBuilderInfo> rows{std::begin(kBuilders), std::end(kBuilders)};
  std::atomic<bool> read{false};
};

BuilderRows& builder_rows() {
  static BuilderRows table;
  return table;
}

}  // namespace

std::span<const BvhBuilderInfo> bvh_builder_table() {
  BuilderRows& table = builder_rows();
  table.read.store(true, std::memory_order_relaxed);
  return table.rows;
}

BvhBuilderKind add_bvh_builder(BvhBuilderInfo row) {
  BuilderRows& table = builder_rows();
  ACCEL_CHECK(!table.read.load(std::memory_order_relaxed) && "add_bvh_builder() after the table was read");
  ACCEL_CHECK(table.rows.size() <= std::numeric_limits<std::underlying_type_t<BvhBuilderKind>>::max());
  row.kind = BvhBuilderKind(table.rows.size());
  table.rows.push_back(row);
  return row.kind;
}

const BvhBuilderInfo& bvh_builder(BvhBuilderKind kind) {
  const std::span<const BvhBuilderInfo> rows = bvh_builder_table();
  for (const BvhBuilderInfo& row : rows)
    if (row.kind == kind) return row;
  ACCEL_CHECK(false && "a BvhBuilderKind without a row in the table");
  return rows[0];
}

const char* builder_name(BvhBuilderKind kind) { return bvh_builder(kind).name; }

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
  return bvh_builder(options.builder).build(scene, options, progress, recorder);
}

}  // namespace accel
