#pragma once
// The one top-down recursion of the BVH builders: "split the node's triangles in two,
// recurse into both halves, stop at a leaf". Every top-down builder is a Splitter class
// over it -- median (bvh_median_builder.cpp), SAH sweep (bvh_sweep_builder.cpp), PCA
// (bvh_pca_builder.cpp), binned SAH (bvh_binned_builder.cpp) and SBVH
// (bvh_spatial_builder.cpp) -- that says only how a node splits; this header owns the rest:
// the leaf rule and its reason (one for every builder), the recorded Node and Leaf steps,
// progress and cancellation, and the leaves' triangle lists. The parallel tasks and their
// stitching are the top-down driver's (top_down_tasks.h). Not a public interface: only the
// builders include it. docs/structures.md, "Adding a BVH builder", walks through a new one.
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

/// Whether a node becomes a leaf, and why.
struct LeafVerdict {
  bool leaf = false;
  LeafReason reason = LeafReason::FewPrims;
};

/// The leaf rule of every top-down builder. A node of `count` references at `depth`, whose
/// best split (if any) costs `split_cost` by the SAH, is a leaf when
///   - it holds one reference, or at most leaf_size and the builder has no SAH rule or no
///     split (FewPrims);
///   - it holds at most leaf_size and its best split is no cheaper than the leaf (NoGain);
///   - it is at the depth limit (MaxDepth): every node there, small or not, that the two
///     rules above would have split.
/// `sah_rule` false (the median split): a small node is a leaf whatever a split costs.
inline LeafVerdict leaf_verdict(const BvhBuildOptions& o, bool sah_rule, size_t count, int depth, bool split_valid,
                                float split_cost) {
  const bool small = count <= size_t(o.leaf_size);
  if (count <= 1 || (small && (!sah_rule || !split_valid))) return {true, LeafReason::FewPrims};
  if (small && split_cost >= o.leaf_cost(count)) return {true, LeafReason::NoGain};
  if (depth >= kMaxBvhDepth - 1) return {true, LeafReason::MaxDepth};
  return {};
}

/// The one recursion, over a Splitter, which provides:
///   using Work;     a node's references as the splitter keeps them (default-constructible,
///                   movable): a range of one shared array, or references of its own (sbvh)
///   using Split;    its split, with `bool valid` and `float cost` (the SAH cost) for the leaf rule
///   using Scratch;  per-task buffers, derived from ScratchBase
///   static constexpr bool kSahLeafRule;  see leaf_verdict()
///   Work root();                                     the root (prepares the splitter's lists)
///   uint64_t progress_total() const;                 progress units of the whole build ...
///   uint64_t progress_units(const Work&) const;      ... and of a leaf
///   size_t count(const Work&) const;                 the node's references
///   Aabb box(const Work&) const;                     the node's box
///   Split split(Scratch&, Work&, const Aabb& box, int depth, uint32_t id);   count >= 2
///   void leaf(const Work&, const Split&, std::vector<uint32_t>& prims) const; appends its triangles
///   void partition(Scratch&, Work&, Split&, Work& left, Work& right, int depth, uint32_t id,
///                  float leaf_cost);   the children's work (consumes the node's), its Split step
///   Aabb node_triangles(const Work&, std::vector<uint32_t>& prims) const;  recording: the
///                                    node's triangles (into prims) and centroid bounds
/// `id` names the node in the recorded steps; the splitter records its Axis and Candidates
/// steps in split() and its Split step in partition().
///
/// Parallel and deterministic through the top-down driver (top_down_tasks.h), whose
/// interface it provides: large subtrees are tasks, the smaller ones serial chunks, each with
/// its leaves' triangles, stitched into one pre-order. Every decision depends only on the
/// node's work, so the tree is the same for any thread count.
///
/// Sink (build_trace.h): NullBuildSink for the normal build; BuildRecorder records every
/// node, axis, candidate sweep, split and leaf. Recording builds the whole tree in one
/// serial chunk, so the event ids are the final pre-order indices.
template <class Splitter, class Sink>
class TopDownBuilder {
 public:
  using Work = typename Splitter::Work;

  TopDownBuilder(const BvhBuildOptions& o, Splitter& splitter, ProgressSpan* progress, Sink& sink)
      : o_(o), splitter_(splitter), progress_(progress, splitter.progress_total()), sink_(sink) {}

  /// The tree; empty when the build was cancelled.
  BuildTree build() {
    BuildTree tree;
    Task root{splitter_.root(), 0};
    const std::unique_ptr<ChunkT> chunks = TopDownTasks<TopDownBuilder>(*this).build(root);
    if (progress_.stopped()) return tree;  // cancelled: the caller discards the tree
    stitch(*chunks, tree.nodes, &tree.prims);
    tree.root = 0;
    return tree;
  }

  // The top-down driver's interface (top_down_tasks.h).
  using Node = BuildNode;
  using Stats = NoChunkStats;
  /// A subtree to build.
  struct Task {
    Work work;
    int depth = 0;
  };
  using ChunkT = Chunk<BuildNode>;
  size_t refs(const Task& t) const { return splitter_.count(t.work); }
  bool all_serial() const { return Sink::kRecords; }  // recording: one chunk, the event ids in pre-order
  bool stopped() const { return progress_.stopped(); }
  void build_serial(Task& t, ChunkT& chunk) {
    Scratch scratch;
    const size_t count = splitter_.count(t.work);
    if constexpr (!Sink::kRecords) chunk.nodes.reserve(2 * count);  // a recorded build is one chunk of any size
    chunk.prims.reserve(count);
    build_subtree(chunk, scratch, t.work, t.depth, kNoBuildNode);
  }
  RootSplit split_root(Task& t, ChunkT& chunk, Task& left, Task& right) {
    Scratch scratch;  // freed before the children allocate theirs
    const BuildNode node = decide(chunk, scratch, t.work, t.depth, 0, kNoBuildNode, left.work, right.work);
    if (node.count) {
      chunk.nodes.push_back(node);
      return RootSplit::Leaf;
    }
    chunk.node = node;
    left.depth = right.depth = t.depth + 1;
    return RootSplit::Split;
  }

 private:
  using Scratch = typename Splitter::Scratch;
  using SplitT = typename Splitter::Split;

  /// The serial recursion: appends the subtree in pre-order, returns its root's index.
  /// `parent` is the parent's index (recorded builds: the event ids are these indices).
  uint32_t build_subtree(ChunkT& chunk, Scratch& scratch, Work& work, int depth, uint32_t parent) {
    const uint32_t index = uint32_t(chunk.nodes.size());
    Work left, right;
    chunk.nodes.push_back(decide(chunk, scratch, work, depth, index, parent, left, right));
    if (chunk.nodes[index].count) return index;
    const uint32_t l = build_subtree(chunk, scratch, left, depth + 1, index);
    const uint32_t r = build_subtree(chunk, scratch, right, depth + 1, index);
    chunk.nodes[index].left = l;
    chunk.nodes[index].right = r;
    return index;
  }

  /// One node: its box, the splitter's split, the leaf rule. A leaf's triangles go to
  /// chunk.prims (its `first` is relative to them); an inner node's children get `left` and
  /// `right`. `id` and `parent` name the node in the recorded steps.
  BuildNode decide(ChunkT& chunk, Scratch& scratch, Work& work, int depth, [[maybe_unused]] uint32_t id,
                   [[maybe_unused]] uint32_t parent, Work& left, Work& right) {
    BuildNode node;
    const size_t count = splitter_.count(work);
    if (progress_.stopped()) {  // cancelled: close the subtree as one leaf (the tree is discarded)
      emit_leaf(chunk, work, SplitT{}, node);
      return node;
    }
    node.box = splitter_.box(work);
    if constexpr (Sink::kRecords) record_node(scratch, work, id, parent, depth, node.box, count);
    SplitT split{};
    if (count > 1) split = splitter_.split(scratch, work, node.box, depth, id);
    const LeafVerdict verdict = leaf_verdict(o_, Splitter::kSahLeafRule, count, depth, split.valid, split.cost);
    if (verdict.leaf) {
      ACCEL_CHECK(count <= size_t(o_.leaf_size) || depth >= kMaxBvhDepth - 1);
      emit_leaf(chunk, work, split, node);
      if constexpr (Sink::kRecords) sink_.leaf(id, verdict.reason, chunk.prims.data() + node.first, count);
      return node;
    }
    splitter_.partition(scratch, work, split, left, right, depth, id, o_.leaf_cost(count));
    return node;
  }

  /// Makes `node` a leaf over the work's triangles, appended to the chunk's, and counts them
  /// for the progress; the work is spent.
  void emit_leaf(ChunkT& chunk, Work& work, const SplitT& split, BuildNode& node) {
    node.first = uint32_t(chunk.prims.size());
    node.count = uint32_t(splitter_.count(work));
    splitter_.leaf(work, split, chunk.prims);
    progress_.add(splitter_.progress_units(work));
    work = Work{};
  }

  /// Node step: its triangles in the order they arrive in, their centroid bounds.
  void record_node(Scratch& scratch, const Work& work, uint32_t id, uint32_t parent, int depth, const Aabb& box,
                   size_t count) {
    if (!sink_.records(depth)) {  // below the depth limit: the sink keeps at most the count
      sink_.node(id, parent, depth, box, Aabb{}, nullptr, count);
      return;
    }
    const Aabb centroids = splitter_.node_triangles(work, scratch.rec_prims);
    sink_.node(id, parent, depth, box, centroids, scratch.rec_prims.data(), count);
  }

  const BvhBuildOptions& o_;
  Splitter& splitter_;
  ProgressCounter progress_;  ///< progress units placed in leaves, of the splitter's total
  Sink& sink_;
};

inline std::vector<PrimRef> make_refs(const Scene& scene) {
  std::vector<PrimRef> refs;
  refs.reserve(scene.valid_prims().size());
  for (uint32_t p : scene.valid_prims()) refs.push_back({scene.triangle_bounds(p), scene.centroid(p), p});
  return refs;
}

/// A node of the splitters over one shared array of PrimRefs: refs [begin, end), arriving
/// in `order` (kRefsOrder, or a splitter's own list).
struct RefRange {
  size_t begin = 0, end = 0;
  int order = kRefsOrder;
};

/// The Work side of the Splitter interface for the splitters over one array of PrimRefs
/// (median, SAH sweep, PCA): Derived provides bounds(order, begin, end), prim(order, k) and
/// centroid(order, k). Progress counts the triangles placed.
template <class Derived, class Sink>
class RefRangeSplitter {
 public:
  using Work = RefRange;
  using Split = top_down::Split;

  RefRangeSplitter(const Scene& scene, const BvhBuildOptions& o, Sink& sink)
      : o_(o), sink_(sink), refs_(make_refs(scene)) {}

  uint64_t progress_total() const { return refs_.size(); }
  uint64_t progress_units(const RefRange& w) const { return w.end - w.begin; }
  size_t count(const RefRange& w) const { return w.end - w.begin; }
  /// The box in the order the references arrive in (min/max of equal values may differ in
  /// the sign of a zero, so the order of the scan is part of the result).
  Aabb box(const RefRange& w) const { return self().bounds(w.order, w.begin, w.end); }
  void leaf(const RefRange& w, const Split& split, std::vector<uint32_t>& prims) const {
    // In the order the split saw them (a single one is in every order).
    const int order = w.end - w.begin > 1 ? split.child_order : w.order;
    for (size_t k = w.begin; k < w.end; ++k) prims.push_back(self().prim(order, k));
  }
  Aabb node_triangles(const RefRange& w, std::vector<uint32_t>& prims) const {
    prims.resize(w.end - w.begin);
    Aabb centroids;
    for (size_t k = w.begin; k < w.end; ++k) {
      prims[k - w.begin] = self().prim(w.order, k);
      centroids.extend(self().centroid(w.order, k));
    }
    return centroids;
  }

 protected:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
  /// The children of `w` after `split`, and its Split step.
  void children(const RefRange& w, const Split& split, RefRange& left, RefRange& right, [[maybe_unused]] uint32_t id,
                [[maybe_unused]] float leaf_cost) {
    if constexpr (Sink::kRecords)
      sink_.split(id, split.plane_axis, split.plane_pos, std::isnan(split.cost) ? split.plane_cost : split.cost,
                  leaf_cost, uint32_t(split.mid - w.begin), uint32_t(w.end - split.mid), 0);
    left = {w.begin, split.mid, split.child_order};
    right = {split.mid, w.end, split.child_order};
  }

  const BvhBuildOptions& o_;
  Sink& sink_;
  std::vector<PrimRef> refs_;
};

/// The splitters that reorder refs in place (median, PCA): a node's references, box and
/// leaf triangles are read from refs itself. A split that is invalid or leaves a side empty
/// falls back to the object median on the longest centroid axis.
template <class Derived, class Sink>
class InPlaceSplitter : public RefRangeSplitter<Derived, Sink> {
 public:
  using Base = RefRangeSplitter<Derived, Sink>;
  using Base::Base;

  RefRange root() { return {0, this->refs_.size(), kRefsOrder}; }
  Aabb bounds(int, size_t begin, size_t end) const { return bounds_of(this->refs_, begin, end); }
  uint32_t prim(int, size_t k) const { return this->refs_[k].prim; }
  const Vec3& centroid(int, size_t k) const { return this->refs_[k].centroid; }

  template <class AnyScratch>
  void partition(AnyScratch&, RefRange& w, Split& split, RefRange& left, RefRange& right, int, uint32_t id,
                 float leaf_cost) {
    if (!split.valid || split.mid <= w.begin || split.mid >= w.end) {
      const int axis = centroid_bounds_of(this->refs_, w.begin, w.end).longest_axis();
      split = object_median_split(this->refs_, w.begin, w.end, axis);
      if constexpr (Sink::kRecords)
        record_median_split(this->sink_, this->o_, this->refs_, id, axis, w.begin, w.end, split);
    }
    this->children(w, split, left, right, id, leaf_cost);
  }
};

/// A top-down build with splitter class template S (constructed from the scene, the options
/// and the sink), recorded into `recorder` when there is one: build_bvh_tree()'s contract.
template <template <class> class S>
BuildTree build_top_down(const Scene& scene, const BvhBuildOptions& o, ProgressSpan* progress,
                         BuildRecorder* recorder) {
  return with_build_sink(recorder, [&](auto& sink) -> BuildTree {
    using Sink = std::remove_reference_t<decltype(sink)>;
    sink.scene_box(scene.bounds());
    if (scene.valid_prims().empty()) return {};
    S<Sink> splitter(scene, o, sink);
    return TopDownBuilder<S<Sink>, Sink>(o, splitter, progress, sink).build();
  });
}

}  // namespace accel::top_down
