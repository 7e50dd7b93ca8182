#pragma once
// The top-down recursion the lecture's median, SAH sweep and PCA builders share
// (bvh_median_builder.cpp, bvh_sweep_builder.cpp, bvh_pca_builder.cpp): "split the node's
// triangles in two, recurse into both halves, stop at a leaf". The builders differ only in
// how they split, a Splitter class each; this header holds the rest -- triangle references,
// the SAH cost, the leaf rule, the object-median fallback, progress and cancellation; the
// parallel tasks and their stitching are the top-down driver's (top_down_tasks.h). Not a
// public interface: only those three builders include it (the binned SAH and SBVH builders
// have their own recursion, bvh_binned_detail.h, under the same driver).
#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "build_control.h"
#include "build_trace.h"
#include "check.h"
#include "geometry.h"
#include "parallel.h"
#include "structures/bvh_build_types.h"
#include "structures/bvh_chunk_links.h"
#include "structures/top_down_tasks.h"

namespace accel::top_down {

/// A triangle as the builders see it: its box, the box centre, its index.
struct PrimRef {
  Aabb box;
  Vec3 centroid;
  uint32_t prim;
};

/// The references of the root are in scene order, and the median and PCA splitters reorder
/// refs in place, so their nodes' references are in refs' own order; the SAH sweep's nodes
/// get theirs in one of its three sorted axis lists (0, 1, 2) instead.
inline constexpr int kRefsOrder = -1;

/// A proposed split of the node's references [begin, end): they are already partitioned so
/// that [begin, mid) go left.
struct Split {
  bool valid = false;
  size_t mid = 0;
  float cost = 0.0f;             ///< SAH cost of the split; NaN for the median split (no SAH)
  int child_order = kRefsOrder;  ///< the order the children's references arrive in
  // Recorded builds only: the plane the viewer draws (axis 3: the PCA direction), and the
  // SAH cost it shows for a median split.
  int plane_axis = 0;
  float plane_pos = 0.0f;
  float plane_cost = 0.0f;
};

/// 1 / the parent's area, the scale of sah_split_cost() (1 for a flat parent).
inline float inverse_parent_area(float parent_area) { return parent_area > 0.0f ? 1.0f / parent_area : 1.0f; }

/// SAH cost of a split from the children's areas and leaf costs; every sweep computes its
/// costs with this one expression, so they agree to the bit.
inline float sah_split_cost_scaled(float ct, float inv_parent_area, float left_area, float left_leaf_cost,
                                   float right_area, float right_leaf_cost) {
  return ct + (left_area * left_leaf_cost + right_area * right_leaf_cost) * inv_parent_area;
}

/// SAH cost of a split with child areas/counts, relative to the parent's area.
inline float sah_split_cost(const BvhBuildOptions& o, float parent_area, float left_area, size_t n_left,
                            float right_area, size_t n_right) {
  return sah_split_cost_scaled(o.ct, inverse_parent_area(parent_area), left_area, o.leaf_cost(n_left), right_area,
                               o.leaf_cost(n_right));
}

inline Aabb bounds_of(const std::vector<PrimRef>& refs, size_t begin, size_t end) {
  Aabb b;
  for (size_t i = begin; i < end; ++i) b.extend(refs[i].box);
  return b;
}

inline Aabb centroid_bounds_of(const std::vector<PrimRef>& refs, size_t begin, size_t end) {
  Aabb b;
  for (size_t i = begin; i < end; ++i) b.extend(refs[i].centroid);
  return b;
}

/// The order of the median split and of the SAH sweep: by centre along `axis`, ties by
/// triangle index, so it is a total order and every sort of a set of references agrees.
inline bool centroid_less(const PrimRef& a, const PrimRef& b, int axis) {
  return a.centroid[axis] < b.centroid[axis] || (a.centroid[axis] == b.centroid[axis] && a.prim < b.prim);
}

/// Splits at the object median along `axis`. Always valid for >= 2 refs, even when all
/// centres coincide (then the order is simply halved), so every builder terminates with a
/// depth of O(log n) in the worst case.
inline Split object_median_split(std::vector<PrimRef>& refs, size_t begin, size_t end, int axis) {
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(refs.begin() + long(begin), refs.begin() + long(mid), refs.begin() + long(end),
                   [axis](const PrimRef& a, const PrimRef& b) { return centroid_less(a, b, axis); });
  return {true, mid, std::nanf("")};
}

/// The unit vector of `axis`, for the recorded axis steps.
inline Vec3 unit_axis(int axis) {
  Vec3 v(0.0f);
  v[axis] = 1.0f;
  return v;
}

/// Records a median split of refs[begin, end) at mid along `axis` (the axis step) and fills
/// the plane of `split`: halfway between the last left and the first right centre, with the
/// split's SAH cost.
template <class Sink>
void record_median_split(Sink& sink, const BvhBuildOptions& o, const std::vector<PrimRef>& refs, uint32_t id,
                         int axis, size_t begin, size_t end, Split& split) {
  const size_t mid = split.mid;
  sink.axis(id, axis, unit_axis(axis));
  float left_max = -kInf;
  for (size_t k = begin; k < mid; ++k) left_max = std::max(left_max, refs[k].centroid[axis]);
  split.plane_axis = axis;
  split.plane_pos = 0.5f * (left_max + refs[mid].centroid[axis]);
  split.plane_cost = sah_split_cost(o, bounds_of(refs, begin, end).area(), bounds_of(refs, begin, mid).area(),
                                    mid - begin, bounds_of(refs, mid, end).area(), end - mid);
}

/// Per-task buffers, reused by every node of a serial subtree: a Splitter's Scratch extends
/// this with its own.
struct ScratchBase {
  // Recorded builds only:
  std::vector<uint32_t> rec_prims;  ///< a node's triangles
  std::vector<float> rec_costs;     ///< the sweeps' costs by position
  std::vector<SplitCandidate> rec_candidates;
};

/// What the median and PCA splitters share: they reorder refs in place, so a node's
/// references, box and leaf triangles are read from refs itself. A Splitter provides:
///   kSahLeafRule   a small node becomes a leaf only when no split is cheaper by the SAH
///                  (false: whenever it is small enough);
///   kInPlace       refs is in node order (the object-median fallback may reorder it);
///   Scratch        its per-task buffers (derived from ScratchBase);
///   prepare(), bounds(order, begin, end), prim(order, k), centroid(order, k),
///   split(scratch, begin, end, box, depth, id), partition(scratch, split, begin, end).
class InPlaceSplitter {
 public:
  static constexpr bool kInPlace = true;
  explicit InPlaceSplitter(std::vector<PrimRef>& refs) : refs_(refs) {}
  void prepare() {}
  Aabb bounds(int, size_t begin, size_t end) const { return bounds_of(refs_, begin, end); }
  uint32_t prim(int, size_t k) const { return refs_[k].prim; }
  const Vec3& centroid(int, size_t k) const { return refs_[k].centroid; }
  template <class AnyScratch>
  void partition(AnyScratch&, const Split&, size_t, size_t) {}

 protected:
  std::vector<PrimRef>& refs_;
};

/// The recursion, over a Splitter (see InPlaceSplitter).
///
/// Parallel and deterministic through the top-down driver (top_down_tasks.h), whose
/// interface it provides: large subtrees are tasks, the smaller ones serial chunks, stitched
/// into one pre-order. Every decision depends only on the references of the node, so the
/// tree is the same for any thread count.
///
/// Sink (build_trace.h): NullBuildSink for the normal build; BuildRecorder records every
/// node, axis, candidate sweep, split and leaf. Recording builds the whole tree in one
/// serial chunk, so the event ids are the final pre-order indices.
template <class Splitter, class Sink>
class TopDownBuilder {
 public:
  TopDownBuilder(const BvhBuildOptions& o, std::vector<PrimRef>& refs, Splitter& splitter, ProgressSpan* progress,
                 Sink& sink)
      : o_(o), refs_(refs), splitter_(splitter), total_(refs.size()), progress_(progress, total_), sink_(sink) {}

  BuildTree build() {
    BuildTree tree;
    prims_.assign(total_, 0);
    splitter_.prepare();
    Task root{0, total_, 0, kRefsOrder};
    const std::unique_ptr<ChunkT> chunks = top_down::TopDownTasks<TopDownBuilder>(*this).build(root);
    top_down::stitch(*chunks, tree.nodes);
    tree.prims = std::move(prims_);
    tree.root = 0;
    return tree;
  }

  // The top-down driver's interface (top_down_tasks.h).
  using Node = BuildNode;
  using Stats = NoChunkStats;
  /// A subtree to build: references [begin, end) arriving in `order`.
  struct Task {
    size_t begin = 0, end = 0;
    int depth = 0;
    int order = kRefsOrder;
  };
  using ChunkT = Chunk<BuildNode>;
  size_t refs(const Task& t) const { return t.end - t.begin; }
  bool all_serial() const { return Sink::kRecords; }  // recording: one chunk, the event ids in pre-order
  bool stopped() const { return progress_.stopped(); }
  void build_serial(Task& t, ChunkT& chunk) {
    Scratch scratch;
    chunk.nodes.reserve(2 * (t.end - t.begin));
    build_serial(chunk.nodes, scratch, t.begin, t.end, t.depth, t.order, kNoBuildNode);
  }
  RootSplit split_root(Task& t, ChunkT& chunk, Task& left, Task& right) {
    Scratch scratch;  // freed before the children allocate theirs
    const Decision d = decide(scratch, t.begin, t.end, t.depth, t.order, 0, kNoBuildNode);
    if (d.leaf) {
      chunk.nodes.push_back(d.node);
      return RootSplit::Leaf;
    }
    chunk.node = d.node;
    left = {t.begin, d.mid, t.depth + 1, d.child_order};
    right = {d.mid, t.end, t.depth + 1, d.child_order};
    return RootSplit::Split;
  }

 private:
  using Scratch = typename Splitter::Scratch;

  /// A node's decision: a leaf, or children [begin, mid) and [mid, end).
  struct Decision {
    BuildNode node;  ///< box, and first/count for a leaf
    bool leaf = true;
    size_t mid = 0;
    int child_order = kRefsOrder;  ///< the order the children's references arrive in
  };

  /// The serial recursion: appends the subtree in pre-order, returns its root's index.
  /// `parent` is the parent's index (recorded builds: the event ids are these indices).
  uint32_t build_serial(std::vector<BuildNode>& nodes, Scratch& scratch, size_t begin, size_t end, int depth,
                        int order, uint32_t parent) {
    const uint32_t index = uint32_t(nodes.size());
    const Decision d = decide(scratch, begin, end, depth, order, index, parent);
    nodes.push_back(d.node);
    if (d.leaf) return index;
    const uint32_t left = build_serial(nodes, scratch, begin, d.mid, depth + 1, d.child_order, index);
    const uint32_t right = build_serial(nodes, scratch, d.mid, end, depth + 1, d.child_order, index);
    nodes[index].left = left;
    nodes[index].right = right;
    return index;
  }

  /// One node: its box, the splitter's split, the leaf rule. `id` and `parent` name the
  /// node in the recorded steps (unused by the normal build).
  Decision decide(Scratch& scratch, size_t begin, size_t end, int depth, int order, [[maybe_unused]] uint32_t id,
                  [[maybe_unused]] uint32_t parent) {
    Decision d;
    const size_t count = end - begin;
    d.node.first = uint32_t(begin);
    d.node.count = uint32_t(count);
    if (progress_.stopped()) {  // cancelled: close the subtree as one leaf (the tree is discarded)
      d.node.box = Aabb{};
      return d;
    }
    // The box in the order the references arrive in (min/max of equal values may differ in
    // the sign of a zero, so the order of the scan is part of the result).
    const Aabb box = splitter_.bounds(order, begin, end);
    d.node.box = box;
    if constexpr (Sink::kRecords) record_node(scratch, id, parent, depth, begin, end, order, box);
    Split split;
    if (count > 1) split = splitter_.split(scratch, begin, end, box, depth, id);
    const bool sah_cost = Splitter::kSahLeafRule;
    const float leaf_cost = o_.leaf_cost(count);
    const bool small = count <= size_t(o_.leaf_size);
    if (count <= 1 || (small && (!sah_cost || !split.valid || split.cost >= leaf_cost)) ||
        depth >= kMaxBvhDepth - 1) {
      ACCEL_CHECK(count <= size_t(o_.leaf_size) || depth >= kMaxBvhDepth - 1);
      // The leaf's triangles in the order the split saw them (a single one is in every order).
      emit_leaf(begin, end, count > 1 ? split.child_order : order);
      if constexpr (Sink::kRecords) {
        const LeafReason reason = count <= 1 ? LeafReason::FewPrims
                                  : !small   ? LeafReason::MaxDepth
                                  : sah_cost && split.valid && split.cost >= leaf_cost ? LeafReason::NoGain
                                                                                       : LeafReason::FewPrims;
        sink_.leaf(id, reason, prims_.data() + begin, count);
      }
      return d;
    }
    if (!split.valid || split.mid <= begin || split.mid >= end) {
      // The SAH sweep's split is always inside the node (it tries every position): only the
      // in-place splitters can get here.
      ACCEL_CHECK(Splitter::kInPlace);
      const int axis = centroid_bounds_of(refs_, begin, end).longest_axis();
      split = object_median_split(refs_, begin, end, axis);
      if constexpr (Sink::kRecords) record_median_split(sink_, o_, refs_, id, axis, begin, end, split);
    }
    if constexpr (Sink::kRecords)
      sink_.split(id, split.plane_axis, split.plane_pos, std::isnan(split.cost) ? split.plane_cost : split.cost,
                  leaf_cost, uint32_t(split.mid - begin), uint32_t(end - split.mid), 0);
    splitter_.partition(scratch, split, begin, end);
    d.node.first = d.node.count = 0;
    d.leaf = false;
    d.mid = split.mid;
    d.child_order = split.child_order;
    return d;
  }

  /// Writes the leaf's triangles to their place in the output and counts them for the
  /// progress.
  void emit_leaf(size_t begin, size_t end, int order) {
    for (size_t k = begin; k < end; ++k) prims_[k] = splitter_.prim(order, k);
    progress_.add(end - begin);
  }

  /// Node step: its triangles in the order they arrive in, their centroid bounds.
  void record_node(Scratch& scratch, uint32_t id, uint32_t parent, int depth, size_t begin, size_t end, int order,
                   const Aabb& box) {
    const size_t n = end - begin;
    if (!sink_.records(depth)) {  // below the depth limit: the sink keeps at most the count
      sink_.node(id, parent, depth, box, Aabb{}, nullptr, n);
      return;
    }
    std::vector<uint32_t>& prims = scratch.rec_prims;
    prims.resize(n);
    Aabb cb;
    for (size_t k = begin; k < end; ++k) {
      prims[k - begin] = splitter_.prim(order, k);
      cb.extend(splitter_.centroid(order, k));
    }
    sink_.node(id, parent, depth, box, cb, prims.data(), n);
  }

  const BvhBuildOptions& o_;
  std::vector<PrimRef>& refs_;
  Splitter& splitter_;
  const size_t total_;
  std::vector<uint32_t> prims_;  ///< the output's triangle list
  ProgressCounter progress_;     ///< triangles placed in leaves, of total_
  Sink& sink_;
};

inline std::vector<PrimRef> make_refs(const Scene& scene) {
  std::vector<PrimRef> refs;
  refs.reserve(scene.valid_prims().size());
  for (uint32_t p : scene.valid_prims()) refs.push_back({scene.triangle_bounds(p), scene.centroid(p), p});
  return refs;
}

/// A top-down build with splitter class template S, recorded into `recorder` when there is
/// one: build_bvh_tree()'s contract.
template <template <class> class S>
BuildTree build_top_down(const Scene& scene, const BvhBuildOptions& o, ProgressSpan* progress,
                         BuildRecorder* recorder) {
  return with_build_sink(recorder, [&](auto& sink) -> BuildTree {
    using Sink = std::remove_reference_t<decltype(sink)>;
    sink.scene_box(scene.bounds());
    std::vector<PrimRef> refs = make_refs(scene);
    if (refs.empty()) return {};
    S<Sink> splitter(o, refs, sink);
    return TopDownBuilder<S<Sink>, Sink>(o, refs, splitter, progress, sink).build();
  });
}

}  // namespace accel::top_down
