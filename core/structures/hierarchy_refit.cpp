// Refit of the binary hierarchies (hierarchy.h): the bounds of the same nodes recomputed from
// moved vertices. Kept out of the header so TBB stays a private dependency of the core;
// instantiated below for the two hierarchies.
#include <type_traits>

#include "parallel.h"
#include "structures/bvh.h"
#include "structures/sphere_tree.h"

namespace accel {
namespace {

/// Subtrees of at most this many nodes are refitted by one task, bottom-up in one loop:
/// below it a task's overhead outweighs the few box unions of its nodes.
constexpr uint32_t kRefitGrain = 2048;

}  // namespace

Status check_refit_prims(const std::string& structure, const Scene& scene, size_t held, uint32_t bad) {
  // A degenerate triangle is never hit (docs/hits.md), but one that turned valid must be in
  // the structure to be hit: the sets must be equal. Every held triangle valid and the
  // counts equal proves it.
  if (bad != ~0u)
    return make_error(structure + " cannot refit: triangle " + std::to_string(bad) +
                      (bad < scene.triangle_count() ? " is degenerate now" : " is not in the scene") + ": rebuild it");
  if (held != scene.valid_prims().size())
    return make_error(structure + " cannot refit: built over " + std::to_string(held) + " valid triangles, the scene has " +
                      std::to_string(scene.valid_prims().size()) +
                      " (a degenerate triangle became valid, or another scene): rebuild it");
  return {};
}

template <class Derived, class Volume, class VolumeRay>
Status Hierarchy<Derived, Volume, VolumeRay>::refit_impl(const Scene& scene) {
  // The first triangle that may not stay (the lowest position, whatever the thread count).
  const size_t bad_at = par::parallel_reduce(
      par::blocked_range<size_t>(0, prims_.size(), 16384), prims_.size(),
      [&](const par::blocked_range<size_t>& r, size_t first) {
        for (size_t k = r.begin(); k < r.end() && k < first; ++k)
          if (!refit_keeps(scene, prims_[k])) return k;
        return first;
      },
      [](size_t a, size_t b) { return std::min(a, b); });
  const uint32_t bad = bad_at < prims_.size() ? prims_[bad_at] : ~0u;
  if (Status s = check_refit_prims(this->name(), scene, triangles_, bad); !s) return s;
  scene_ = &scene;  // the sphere fits below read the moved vertices through it
  if (!nodes_.empty()) {
    // A box is its own volume: one pass. Spheres are fitted as fit_volumes() fits them
    // (fit_levels()), from the triangle ranges the bottom-up pass records: a second pass,
    // once every node's box exists.
    constexpr bool kVolumeIsBox = std::is_same_v<Volume, Aabb>;
    std::vector<PrimRange> ranges(kVolumeIsBox ? 0 : nodes_.size());
    refit_subtree(scene, 0, uint32_t(nodes_.size()), kVolumeIsBox ? nullptr : ranges.data());
    if constexpr (!kVolumeIsBox) fit_levels(ranges.data(), nullptr);
  }
  return {};
}

template <class Derived, class Volume, class VolumeRay>
void Hierarchy<Derived, Volume, VolumeRay>::refit_subtree(const Scene& scene, uint32_t node, uint32_t end,
                                                          PrimRange* ranges) {
  if (end - node <= kRefitGrain) {
    // Children have larger ids than their parent: a reverse sweep is bottom-up.
    for (uint32_t k = end; k-- > node;) refit_node(scene, k, ranges);
    return;
  }
  // More than one node: an inner node, its left subtree [node + 1, right), its right [right, end).
  const uint32_t right = nodes_[node].index;
  par::parallel_invoke([&] { refit_subtree(scene, node + 1, right, ranges); },
                       [&] { refit_subtree(scene, right, end, ranges); });
  refit_node(scene, node, ranges);
}

template <class Derived, class Volume, class VolumeRay>
void Hierarchy<Derived, Volume, VolumeRay>::refit_node(const Scene& scene, uint32_t k, PrimRange* ranges) {
  Node& n = nodes_[k];
  Aabb box;
  PrimRange range{0, 0};
  if (n.leaf()) {
    for (uint32_t i = n.index; i < n.index + n.count; ++i) box.extend(scene.triangle_bounds(prims_[i]));
    range = {n.index, n.index + n.count};
  } else {
    box = merge(boxes_[k + 1], boxes_[n.index]);
    // As fit_volumes(): the lowest and highest triangle below, whichever child holds them.
    if (ranges)
      range = {std::min(ranges[k + 1].first, ranges[n.index].first), std::max(ranges[k + 1].end, ranges[n.index].end)};
  }
  boxes_[k] = box;
  if (ranges) ranges[k] = range;
  if constexpr (std::is_same_v<Volume, Aabb>) n.volume = box;
}

template <class Derived, class Volume, class VolumeRay>
bool Hierarchy<Derived, Volume, VolumeRay>::fit_volumes(ProgressSpan* span) {
  // Each node's triangle range, bottom-up: children have larger ids than their parent.
  // Leaves below a node are contiguous in prims_ because flattening is depth-first and
  // every builder lays out a subtree's triangles contiguously.
  std::vector<PrimRange> ranges(nodes_.size());
  for (size_t k = nodes_.size(); k-- > 0;) {
    const Node& n = nodes_[k];
    ranges[k] = n.leaf() ? PrimRange{n.index, n.index + n.count}
                         : PrimRange{std::min(ranges[k + 1].first, ranges[n.index].first),
                                     std::max(ranges[k + 1].end, ranges[n.index].end)};
  }
  if constexpr (!std::is_same_v<Volume, Aabb>) return fit_levels(ranges.data(), span);
  // Boxes: every node's is its own (flatten() set it). Batches, so that the build thread can
  // report progress and notice a cancel between them.
  constexpr size_t kFitBatch = 8192;
  for (size_t begin = 0; begin < nodes_.size(); begin += kFitBatch) {
    const size_t end = std::min(nodes_.size(), begin + kFitBatch);
    par::parallel_for(par::blocked_range<size_t>(begin, end, 64), [&](const par::blocked_range<size_t>& r) {
      for (size_t k = r.begin(); k < r.end(); ++k)
        nodes_[k].volume =
            Derived::fit(*scene_, prims_.data() + ranges[k].first, ranges[k].end - ranges[k].first, boxes_[k]);
    });
    if (span && !span->advance(double(end) / double(nodes_.size()))) return false;
  }
  return true;
}

template <class Derived, class Volume, class VolumeRay>
bool Hierarchy<Derived, Volume, VolumeRay>::fit_levels(const PrimRange* ranges, ProgressSpan* span) {
  // The nodes by depth, deepest first: a level's nodes depend only on deeper ones (their
  // subtrees), so each level is one parallel loop, and the result is the serial one.
  int max_depth = 0;
  for (uint16_t d : depth_) max_depth = std::max(max_depth, int(d));
  std::vector<uint32_t> level_start(size_t(max_depth) + 2, 0);
  for (uint16_t d : depth_) ++level_start[size_t(max_depth - d) + 1];
  for (size_t l = 1; l < level_start.size(); ++l) level_start[l] += level_start[l - 1];
  std::vector<uint32_t> order(nodes_.size());
  {
    std::vector<uint32_t> next(level_start.begin(), level_start.end() - 1);
    for (uint32_t k = 0; k < uint32_t(nodes_.size()); ++k) order[next[size_t(max_depth - depth_[k])]++] = k;
  }
  const Derived& derived = static_cast<const Derived&>(*this);
  for (size_t l = 0; l + 1 < level_start.size(); ++l) {
    par::parallel_for(par::blocked_range<uint32_t>(level_start[l], level_start[l + 1], 32),
                      [&](const par::blocked_range<uint32_t>& r) {
                        for (uint32_t i = r.begin(); i < r.end(); ++i) {
                          const uint32_t k = order[i];
                          const size_t n = ranges[k].end - ranges[k].first;
                          nodes_[k].volume = nodes_[k].leaf() || n <= Derived::kDirectFit
                                                 ? Derived::fit(*scene_, prims_.data() + ranges[k].first, n, boxes_[k])
                                                 : derived.fit_inner(k);
                        }
                      });
    if (span && !span->advance(double(level_start[l + 1]) / double(nodes_.size()))) return false;
  }
  return true;
}

template bool Hierarchy<BinaryBvh, Aabb, BoxTester>::fit_volumes(ProgressSpan*);
template bool Hierarchy<SphereTree, BoundingSphere, SphereRay>::fit_volumes(ProgressSpan*);
template Status Hierarchy<BinaryBvh, Aabb, BoxTester>::refit_impl(const Scene&);
template Status Hierarchy<SphereTree, BoundingSphere, SphereRay>::refit_impl(const Scene&);

}  // namespace accel
