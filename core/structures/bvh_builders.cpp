// BVH builders. Index:
//   [SECTION] Names
//   [SECTION] Shared top-down framework (parallel recursion, leaf rule, fallback split, progress)
//   [SECTION] Median split
//   [SECTION] SAH sweep (all three axes) and PCA sweep
//   [SECTION] Binned SAH: see bvh_binned_builder.cpp; spatial splits (sbvh): bvh_spatial_builder.cpp
//   [SECTION] Bottom-up: locally-ordered clustering
//   [SECTION] Insertion (Goldsmith-Salmon)
//   [SECTION] Collapse, depth limit and final layout for the bottom-up builders
#include "geometry.h"
#include "structures/bvh_builders.h"

#include "structures/bvh_binned_builder.h"
#include "structures/bvh_spatial_builder.h"

#include <emmintrin.h>  // SSE2: part of every x86-64 CPU (as in geometry.h)

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <numeric>
#include <thread>
#include <utility>

#include "bit_cast.h"
#include "check.h"
#include "parallel.h"
#include "random.h"

namespace accel {

// ============================================================================
// [SECTION] Names
// ============================================================================

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

namespace {

// ============================================================================
// [SECTION] Shared top-down framework
// ============================================================================

/// A triangle as the builders see it: its box, the box centre, its index.
struct PrimRef {
  Aabb box;
  Vec3 centroid;
  uint32_t prim;
};

/// A proposed split of refs[begin, end): refs are already partitioned so that
/// [begin, mid) go left. cost is the SAH cost of splitting (NaN for non-SAH splitters).
struct Split {
  bool valid = false;
  size_t mid = 0;
  float cost = 0.0f;
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
float sah_split_cost(const BvhBuildOptions& o, float parent_area, float left_area, size_t n_left, float right_area,
                     size_t n_right) {
  return sah_split_cost_scaled(o.ct, inverse_parent_area(parent_area), left_area, o.leaf_cost(n_left), right_area,
                               o.leaf_cost(n_right));
}

Aabb bounds_of(const std::vector<PrimRef>& refs, size_t begin, size_t end) {
  Aabb b;
  for (size_t i = begin; i < end; ++i) b.extend(refs[i].box);
  return b;
}

Aabb centroid_bounds_of(const std::vector<PrimRef>& refs, size_t begin, size_t end) {
  Aabb b;
  for (size_t i = begin; i < end; ++i) b.extend(refs[i].centroid);
  return b;
}

/// The order of the median split and of the SAH sweep: by centre along `axis`, ties by
/// triangle index, so it is a total order and every sort of a set of references agrees.
inline bool centroid_less(const PrimRef& a, const PrimRef& b, int axis) {
  return a.centroid[axis] < b.centroid[axis] || (a.centroid[axis] == b.centroid[axis] && a.prim < b.prim);
}

/// Splits at the object median along the longest centroid axis. Always valid for >= 2
/// refs, even when all centres coincide (then the order is simply halved), so every builder
/// terminates with a depth of O(log n) in the worst case.
Split object_median_split(std::vector<PrimRef>& refs, size_t begin, size_t end, int axis) {
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(refs.begin() + long(begin), refs.begin() + long(mid), refs.begin() + long(end),
                   [axis](const PrimRef& a, const PrimRef& b) { return centroid_less(a, b, axis); });
  return {true, mid, std::nanf("")};
}

/// Sweeps the n refs base[order[0..n)] in that order: the best split position (reported as
/// begin + i) and its cost. The first minimum wins. `right_area` is scratch. kCosts (recorded
/// builds): costs[i] = the cost of position i, for i in [1, n).
template <bool kCosts = false>
Split sweep_order(const BvhBuildOptions& o, const PrimRef* base, const uint32_t* order, size_t n, size_t begin,
                  float parent_area, std::vector<float>& right_area, [[maybe_unused]] float* costs = nullptr) {
  right_area.resize(n);
  Aabb acc;
  for (size_t i = n; i-- > 1;) {
    acc.extend(base[order[i]].box);
    right_area[i] = acc.area();
  }
  Split best;
  acc = Aabb{};
  for (size_t i = 1; i < n; ++i) {
    acc.extend(base[order[i - 1]].box);
    const float cost = sah_split_cost(o, parent_area, acc.area(), i, right_area[i], n - i);
    if constexpr (kCosts) costs[i] = cost;
    if (!best.valid || cost < best.cost) best = {true, begin + i, cost};
  }
  return best;
}

/// Sorts `items` stably by their upper 32 bits: an LSD radix sort, three passes of 11 bits.
/// `scratch` is a buffer.
void stable_sort_by_upper_half(std::vector<uint64_t>& items, std::vector<uint64_t>& scratch) {
  constexpr int kDigitBits = 11;
  constexpr uint64_t kDigitMask = (1u << kDigitBits) - 1;
  scratch.resize(items.size());
  for (int shift = 32; shift < 64; shift += kDigitBits) {
    std::array<size_t, kDigitMask + 1> start{};
    for (uint64_t v : items) ++start[(v >> shift) & kDigitMask];
    size_t sum = 0;
    for (size_t& s : start) sum += std::exchange(s, sum);
    for (uint64_t v : items) scratch[start[(v >> shift) & kDigitMask]++] = v;
    items.swap(scratch);
  }
}

/// A reference in a sorted axis list of the SAH sweep: its box inline (the sweeps read the
/// lists front to back instead of gathering from PrimRef), the triangle index in the spare
/// lane of `lo`.
struct alignas(16) SweepRef {
  float lo[3];
  uint32_t prim;
  float hi[3];
  float pad = 0.0f;
};
static_assert(sizeof(SweepRef) == 32);

/// A box as two SSE registers, extended and measured exactly as Aabb is: _mm_min_ps(p, acc)
/// is glm::min(acc, p) lane by lane ((p < acc) ? p : acc, which decides even the sign of an
/// equal zero the same way), and area() performs Aabb::area()'s operations in its order.
/// Lane 3 is kept at 0.
struct SweepBox {
  __m128 lo = _mm_set1_ps(kInf);
  __m128 hi = _mm_set1_ps(-kInf);

  void extend(const SweepRef& r) {
    const __m128 xyz = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));  // drops the index lane
    lo = _mm_min_ps(_mm_and_ps(_mm_load_ps(r.lo), xyz), lo);
    hi = _mm_max_ps(_mm_load_ps(r.hi), hi);
  }
  /// Aabb::area() of a non-empty box: 2 * (ex * ey + ey * ez + ez * ex).
  float area() const {
    const __m128 e = _mm_sub_ps(hi, lo);
    const __m128 p = _mm_mul_ps(e, _mm_shuffle_ps(e, e, _MM_SHUFFLE(3, 0, 2, 1)));  // ex*ey, ey*ez, ez*ex
    const __m128 sum = _mm_add_ss(_mm_add_ss(p, _mm_shuffle_ps(p, p, 1)), _mm_shuffle_ps(p, p, 2));
    return _mm_cvtss_f32(_mm_mul_ss(_mm_set_ss(2.0f), sum));
  }
  Aabb aabb() const { return aabb_from_lanes(lo, hi); }
};

/// Top-down recursion shared by the median, SAH and PCA builders (the binned SAH builder has
/// its own recursion in bvh_binned_builder.cpp).
///
/// Parallel and deterministic: subtrees of more than kTaskThreshold references are TBB
/// tasks, each building into its own Chunk in local pre-order; place_chunks() then gives
/// every chunk its offset in the global pre-order (the order of the serial recursion: node,
/// left subtree, right subtree) and relocates them in parallel. Every decision depends only
/// on the references of the node, so the tree is the same for any thread count.
///
/// The SAH sweep (MacDonald & Booth 1990) sorts once: the references are sorted by centre
/// on each axis at the root, and each node's three sorted lists are split by stable
/// partitioning (a flag per reference marks the left side), so a node of n references costs
/// O(n) instead of three sorts. The order on an axis is a total order (centroid_less), so a
/// node's list is exactly what sorting its references would give, and the splits, costs
/// and leaf orders are those of sorting per node.
///
/// Sink (build_trace.h): NullBuildSink for the normal build; BuildRecorder records every
/// node, axis, candidate sweep, split and leaf. Recording builds the whole tree in one
/// serial chunk, so the event ids are the final pre-order indices.
template <class Sink>
class TopDownBuilder {
 public:
  TopDownBuilder(const BvhBuildOptions& o, std::vector<PrimRef>& refs, ProgressSpan* progress, Sink& sink)
      : o_(o), refs_(refs), total_(refs.size()), progress_(progress), reporter_(std::this_thread::get_id()),
        sink_(sink) {}

  BuildTree build() {
    BuildTree tree;
    prims_.assign(total_, 0);
    if (o_.builder == BvhBuilderKind::Sah) sort_axis_lists();
    const std::unique_ptr<Chunk> root = build_chunk(0, total_, 0, kRootOrder);
    tree.nodes.resize(root->size);
    place_chunks(*root, tree.nodes);
    tree.prims = std::move(prims_);
    tree.root = 0;
    return tree;
  }

 private:
  /// Subtrees with at most this many references are one serial task (below it, the task
  /// overhead outweighs the work).
  static constexpr size_t kTaskThreshold = 4096;
  /// order_axis of the root: its references are in scene order.
  static constexpr int kRootOrder = -1;

  /// Per-task buffers, reused by every node of a serial subtree.
  struct Scratch {
    std::vector<float> right_area;
    std::vector<uint32_t> order;
    std::vector<double> key;
    std::vector<PrimRef> refs;
    std::vector<SweepRef> right_side;
    // Recorded builds only:
    std::vector<uint32_t> rec_prims;         ///< a node's triangles
    std::vector<float> rec_costs;            ///< the sweeps' costs by position ([3 * i + axis] for SAH)
    std::vector<SplitCandidate> rec_candidates;
  };

  /// A subtree built by one task. Serial: `nodes` is the whole subtree in local pre-order
  /// (child links relative to nodes[0]). Parallel: `nodes` is its root alone, whose
  /// children are the chunks `left` and `right`.
  struct Chunk {
    std::vector<BuildNode> nodes;
    std::unique_ptr<Chunk> left, right;
    size_t size = 0;  ///< nodes in the subtree
  };

  /// A node's decision: a leaf, or children [begin, mid) and [mid, end).
  struct Decision {
    BuildNode node;  ///< box, and first/count for a leaf
    bool leaf = true;
    size_t mid = 0;
    int child_order = kRootOrder;  ///< SAH: the axis list the children's references arrive in
  };

  std::unique_ptr<Chunk> build_chunk(size_t begin, size_t end, int depth, int order_axis) {
    auto chunk = std::make_unique<Chunk>();
    Scratch scratch;
    if (Sink::kRecords || end - begin <= kTaskThreshold) {  // recording: one serial chunk, in pre-order
      chunk->nodes.reserve(2 * (end - begin));
      build_serial(chunk->nodes, scratch, begin, end, depth, order_axis, kNoBuildNode);
      chunk->size = chunk->nodes.size();
      return chunk;
    }
    const Decision d = decide(scratch, begin, end, depth, order_axis, 0, kNoBuildNode);
    scratch = Scratch{};  // the children allocate their own: free the big buffers first
    chunk->nodes.push_back(d.node);
    chunk->size = 1;
    if (d.leaf) return chunk;
    par::parallel_invoke([&] { chunk->left = build_chunk(begin, d.mid, depth + 1, d.child_order); },
                         [&] { chunk->right = build_chunk(d.mid, end, depth + 1, d.child_order); });
    chunk->size += chunk->left->size + chunk->right->size;
    return chunk;
  }

  /// The serial recursion: appends the subtree in pre-order, returns its root's index.
  /// `parent` is the parent's index (recorded builds: the event ids are these indices).
  uint32_t build_serial(std::vector<BuildNode>& nodes, Scratch& scratch, size_t begin, size_t end, int depth,
                        int order_axis, uint32_t parent) {
    const uint32_t index = uint32_t(nodes.size());
    const Decision d = decide(scratch, begin, end, depth, order_axis, index, parent);
    nodes.push_back(d.node);
    if (d.leaf) return index;
    const uint32_t left = build_serial(nodes, scratch, begin, d.mid, depth + 1, d.child_order, index);
    const uint32_t right = build_serial(nodes, scratch, d.mid, end, depth + 1, d.child_order, index);
    nodes[index].left = left;
    nodes[index].right = right;
    return index;
  }

  /// Gives each chunk its offset in the global pre-order, links the parallel nodes, then
  /// copies the serial chunks to their place in parallel.
  void place_chunks(const Chunk& root, std::vector<BuildNode>& out) const {
    std::vector<std::pair<const Chunk*, uint32_t>> serial;
    std::vector<std::pair<const Chunk*, uint32_t>> stack{{&root, 0}};
    while (!stack.empty()) {
      const auto [c, offset] = stack.back();
      stack.pop_back();
      if (!c->left) {
        serial.push_back({c, offset});
        continue;
      }
      BuildNode& n = out[offset];
      n = c->nodes[0];
      n.left = offset + 1;
      n.right = offset + 1 + uint32_t(c->left->size);
      stack.push_back({c->left.get(), n.left});
      stack.push_back({c->right.get(), n.right});
    }
    par::parallel_for(size_t(0), serial.size(), [&](size_t k) {
      const auto [c, offset] = serial[k];
      BuildNode* dst = out.data() + offset;
      for (const BuildNode& n : c->nodes) {
        *dst = n;
        if (n.count == 0) {
          dst->left += offset;
          dst->right += offset;
        }
        ++dst;
      }
    });
  }

  // --------------------------------------------------------------------------
  // One node: bounds, split, leaf rule
  // --------------------------------------------------------------------------

  /// `id` and `parent` name the node in the recorded steps (unused by the normal build).
  Decision decide(Scratch& scratch, size_t begin, size_t end, int depth, int order_axis,
                  [[maybe_unused]] uint32_t id, [[maybe_unused]] uint32_t parent) {
    Decision d;
    const size_t count = end - begin;
    d.node.first = uint32_t(begin);
    d.node.count = uint32_t(count);
    if (stopped()) {  // cancelled: close the subtree as one leaf (the tree is discarded)
      d.node.box = Aabb{};
      return d;
    }
    // The box in the order the references arrive in (min/max of equal values may differ in
    // the sign of a zero, so the order of the scan is part of the result).
    const bool sah = o_.builder == BvhBuilderKind::Sah;
    const Aabb box = sah && order_axis != kRootOrder ? bounds_of_list(order_axis, begin, end)
                                                     : bounds_of(refs_, begin, end);
    d.node.box = box;
    if constexpr (Sink::kRecords) record_node(scratch, id, parent, depth, begin, end, order_axis, box);
    Split split;
    int sweep_axis = 0;
    if (count > 1) {
      switch (o_.builder) {
        case BvhBuilderKind::Median: split = median_split(begin, end, depth, id); break;
        case BvhBuilderKind::PcaSah: split = pca_split(scratch, begin, end, box, depth, id); break;
        default: split = sweep_split(scratch, begin, end, box, &sweep_axis, depth, id); break;
      }
    }
    const bool sah_cost = o_.builder != BvhBuilderKind::Median;
    const float leaf_cost = o_.leaf_cost(count);
    const bool small = count <= size_t(o_.leaf_size);
    if (count <= 1 || (small && (!sah_cost || !split.valid || split.cost >= leaf_cost)) ||
        depth >= kMaxBvhDepth - 1) {
      ACCEL_CHECK(count <= size_t(o_.leaf_size) || depth >= kMaxBvhDepth - 1);
      emit_leaf(begin, end, sah ? sweep_axis : kRootOrder);
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
      // The sweep's split is always inside the node (it tries every position): only the
      // median and PCA builders can get here, and they work on refs_ in place.
      ACCEL_CHECK(!sah);
      const int axis = centroid_bounds_of(refs_, begin, end).longest_axis();
      split = object_median_split(refs_, begin, end, axis);
      if constexpr (Sink::kRecords) record_median(id, axis, begin, split.mid, end);
    }
    if constexpr (Sink::kRecords)
      sink_.split(id, rec_axis_, rec_pos_, std::isnan(split.cost) ? rec_cost_ : split.cost, leaf_cost,
                  uint32_t(split.mid - begin), uint32_t(end - split.mid), 0);
    if (sah) partition_axis_lists(scratch, sweep_axis, begin, split.mid, end);
    d.node.first = d.node.count = 0;
    d.leaf = false;
    d.mid = split.mid;
    d.child_order = sah ? sweep_axis : kRootOrder;
    return d;
  }

  /// Writes the leaf's triangles to their place in the output (the SAH builder takes them
  /// from the winning axis list, the others from refs_, which they reorder in place) and
  /// counts them for the progress.
  void emit_leaf(size_t begin, size_t end, int list_axis) {
    if (list_axis != kRootOrder) {
      const SweepRef* list = lists_[list_axis].data();
      for (size_t k = begin; k < end; ++k) prims_[k] = list[k].prim;
    } else {
      for (size_t k = begin; k < end; ++k) prims_[k] = refs_[k].prim;
    }
    placed(end - begin);
  }

  // --------------------------------------------------------------------------
  // Progress and cancellation
  // --------------------------------------------------------------------------

  /// Counts triangles placed in leaves; only the thread that started the build reports
  /// (ProgressSpan is not thread-safe), the others just add to the count.
  void placed(size_t n) {
    if (!progress_) return;
    const size_t done = placed_.fetch_add(n, std::memory_order_relaxed) + n;
    if (std::this_thread::get_id() != reporter_ || stop_.load(std::memory_order_relaxed)) return;
    if (!progress_->advance(double(done) / double(total_))) stop_.store(true, std::memory_order_relaxed);
  }

  /// True once the build was cancelled. Any thread: ProgressSpan::cancelled() only reads
  /// the control's atomic flag.
  bool stopped() const {
    return progress_ && (stop_.load(std::memory_order_relaxed) || progress_->cancelled());
  }

  // --------------------------------------------------------------------------
  // [SECTION] Median split
  // --------------------------------------------------------------------------
  Split median_split(size_t begin, size_t end, int depth, [[maybe_unused]] uint32_t id) {
    int axis = 0;
    if (o_.axis == MedianAxis::RoundRobin) axis = depth % 3;
    if (o_.axis == MedianAxis::Longest) axis = centroid_bounds_of(refs_, begin, end).longest_axis();
    const Split s = object_median_split(refs_, begin, end, axis);
    if constexpr (Sink::kRecords) record_median(id, axis, begin, s.mid, end);
    return s;
  }

  // --------------------------------------------------------------------------
  // Recorded builds: the steps' arguments (only instantiated for a recording sink)
  // --------------------------------------------------------------------------

  static Vec3 unit(int axis) {
    Vec3 v(0.0f);
    v[axis] = 1.0f;
    return v;
  }

  /// The centre of a triangle of the SAH lists (refs_ stays in scene order there).
  const Vec3& centroid_of_prim(uint32_t prim) const { return refs_[ref_of_prim_[prim]].centroid; }

  /// Node step: its triangles in the order they arrive in, their centroid bounds.
  void record_node(Scratch& scratch, uint32_t id, uint32_t parent, int depth, size_t begin, size_t end,
                   int order_axis, const Aabb& box) {
    const size_t n = end - begin;
    if (!sink_.records(depth)) {  // below the depth limit: the sink keeps at most the count
      sink_.node(id, parent, depth, box, Aabb{}, nullptr, n);
      return;
    }
    std::vector<uint32_t>& prims = scratch.rec_prims;
    prims.resize(n);
    Aabb cb;
    if (order_axis != kRootOrder) {
      for (size_t k = begin; k < end; ++k) {
        prims[k - begin] = lists_[order_axis][k].prim;
        cb.extend(centroid_of_prim(prims[k - begin]));
      }
    } else {
      for (size_t k = begin; k < end; ++k) {
        prims[k - begin] = refs_[k].prim;
        cb.extend(refs_[k].centroid);
      }
    }
    sink_.node(id, parent, depth, box, cb, prims.data(), n);
  }

  /// Median split of refs_[begin, end) at mid along `axis`: the axis step; the plane is
  /// halfway between the last left and the first right centre, the cost the split's SAH cost.
  void record_median(uint32_t id, int axis, size_t begin, size_t mid, size_t end) {
    sink_.axis(id, axis, unit(axis));
    float left_max = -kInf;
    for (size_t k = begin; k < mid; ++k) left_max = std::max(left_max, refs_[k].centroid[axis]);
    rec_axis_ = axis;
    rec_pos_ = 0.5f * (left_max + refs_[mid].centroid[axis]);
    rec_cost_ = sah_split_cost(o_, bounds_of(refs_, begin, end).area(), bounds_of(refs_, begin, mid).area(),
                               mid - begin, bounds_of(refs_, mid, end).area(), end - mid);
  }

  // --------------------------------------------------------------------------
  // [SECTION] SAH sweep (all three axes) and PCA sweep
  // --------------------------------------------------------------------------

  /// The root's three sorted lists. A node owns the same range [begin, end) of all three
  /// (the children get its two halves), so tasks never touch the same entries.
  void sort_axis_lists() {
    left_.assign(refs_.back().prim + 1, 0);
    if constexpr (Sink::kRecords) {
      ref_of_prim_.assign(refs_.back().prim + 1, 0);
      for (size_t i = 0; i < total_; ++i) ref_of_prim_[refs_[i].prim] = uint32_t(i);
    }
    leaf_costs_.resize(total_ + 1);
    for (size_t k = 0; k <= total_; ++k) leaf_costs_[k] = o_.leaf_cost(k);
    // A stable sort by the centre, as an order-preserving integer, of the references in
    // increasing triangle order gives centroid_less's order (ties by triangle index); -0
    // is folded into +0 because the float comparison holds them equal. Centres are never
    // NaN (the loader rejects non-finite coordinates; an overflowing centre is an infinity,
    // which orders).
    ACCEL_CHECK(std::is_sorted(refs_.begin(), refs_.end(),
                               [](const PrimRef& a, const PrimRef& b) { return a.prim < b.prim; }));
    par::parallel_for(0, 3, [&](int axis) {
      std::vector<uint64_t> keys(total_), scratch;
      for (size_t i = 0; i < total_; ++i) {
        float c = refs_[i].centroid[axis];
        if (c == 0.0f) c = 0.0f;
        const uint32_t bits = accel::bit_cast<uint32_t>(c);
        const uint32_t ordered = bits & 0x80000000u ? ~bits : bits | 0x80000000u;
        keys[i] = (uint64_t(ordered) << 32) | uint64_t(i);
      }
      stable_sort_by_upper_half(keys, scratch);
      std::vector<SweepRef>& list = lists_[axis];
      list.resize(total_);
      par::parallel_for(size_t(0), total_, [&](size_t i) {
        const uint32_t ref = uint32_t(keys[i]);
        const Aabb& b = refs_[ref].box;
        list[i] = {{b.min.x, b.min.y, b.min.z}, refs_[ref].prim, {b.max.x, b.max.y, b.max.z}};
      });
    });
  }

  Aabb bounds_of_list(int axis, size_t begin, size_t end) const {
    SweepBox b;
    for (size_t i = begin; i < end; ++i) b.extend(lists_[axis][i]);
    return b.aabb();
  }

  /// Lecture: "try all 3 axes, search for the minimum along each axis, choose the smallest".
  /// This is sweep_order() on each axis list, the three sweeps interleaved (independent
  /// dependency chains, so the CPU overlaps them), with the boxes read in place and the leaf
  /// costs from a table (the same floats as leaf_cost(), without its division). As there,
  /// the first minimum of an axis wins, and on equal costs the lower axis.
  Split sweep_split(Scratch& scratch, size_t begin, size_t end, const Aabb& box, int* best_axis,
                    [[maybe_unused]] int depth, [[maybe_unused]] uint32_t id) {
    const size_t n = end - begin;  // >= 2
    [[maybe_unused]] float* rec_costs = nullptr;  // recorded builds: every position's cost
    if constexpr (Sink::kRecords) {
      if (sink_.records(depth)) {
        scratch.rec_costs.resize(3 * n);
        rec_costs = scratch.rec_costs.data();
      }
    }
    const SweepRef* list[3] = {lists_[0].data() + begin, lists_[1].data() + begin, lists_[2].data() + begin};
    std::vector<float>& right_area = scratch.right_area;  // [3 * i + axis]: area of positions [i, n)
    right_area.resize(3 * n);
    SweepBox acc[3];
    for (size_t i = n; i-- > 1;) {
      for (int axis = 0; axis < 3; ++axis) {
        acc[axis].extend(list[axis][i]);
        right_area[3 * i + axis] = acc[axis].area();
      }
    }
    const float inv = inverse_parent_area(box.area()), ct = o_.ct;
    const float* leaf_cost = leaf_costs_.data();
    // Position 1 seeds the minimum unconditionally (sweep_order() takes its first cost even
    // when it is NaN); later positions replace it only when strictly cheaper.
    float best_cost[3];
    size_t best_i[3] = {1, 1, 1};
    for (int axis = 0; axis < 3; ++axis) {
      acc[axis] = SweepBox{};
      acc[axis].extend(list[axis][0]);
      best_cost[axis] =
          sah_split_cost_scaled(ct, inv, acc[axis].area(), leaf_cost[1], right_area[3 + axis], leaf_cost[n - 1]);
      if constexpr (Sink::kRecords)
        if (rec_costs) rec_costs[3 + axis] = best_cost[axis];
    }
    for (size_t i = 2; i < n; ++i) {
      const float left_leaf = leaf_cost[i], right_leaf = leaf_cost[n - i];
      for (int axis = 0; axis < 3; ++axis) {
        acc[axis].extend(list[axis][i - 1]);
        const float cost =
            sah_split_cost_scaled(ct, inv, acc[axis].area(), left_leaf, right_area[3 * i + axis], right_leaf);
        if constexpr (Sink::kRecords)
          if (rec_costs) rec_costs[3 * i + axis] = cost;
        if (cost < best_cost[axis]) {
          best_cost[axis] = cost;
          best_i[axis] = i;
        }
      }
    }
    int winner = 0;
    for (int axis = 1; axis < 3; ++axis)
      if (best_cost[axis] < best_cost[winner]) winner = axis;
    *best_axis = winner;
    if constexpr (Sink::kRecords) {
      // Candidates of every axis in sweep order: position i (i references left) is the plane
      // halfway between the centres of the i-th and (i+1)-th reference in the axis order.
      std::vector<SplitCandidate>& cands = scratch.rec_candidates;
      for (int axis = 0; axis < 3 && rec_costs; ++axis) {
        cands.resize(n - 1);
        for (size_t i = 1; i < n; ++i)
          cands[i - 1] = {0.5f * (centroid_of_prim(list[axis][i - 1].prim)[axis] +
                                  centroid_of_prim(list[axis][i].prim)[axis]),
                          rec_costs[3 * i + axis], uint32_t(i), uint32_t(n - i)};
        sink_.candidates(id, axis, cands.data(), cands.size());
      }
      sink_.axis(id, winner, unit(winner));
      const size_t i = best_i[winner];
      rec_axis_ = winner;
      rec_pos_ = 0.5f * (centroid_of_prim(list[winner][i - 1].prim)[winner] +
                         centroid_of_prim(list[winner][i].prim)[winner]);
    }
    return {true, begin + best_i[winner], best_cost[winner]};
  }

  /// Hands the children their sorted lists: the winning axis list is already split at
  /// `mid`; the other two are partitioned stably, in place, by the side of each reference
  /// (left ones compact to the front, right ones wait in scratch).
  void partition_axis_lists(Scratch& scratch, int split_axis, size_t begin, size_t mid, size_t end) {
    const SweepRef* split_list = lists_[split_axis].data();
    uint8_t* left = left_.data();
    for (size_t k = begin; k < mid; ++k) left[split_list[k].prim] = 1;
    for (size_t k = mid; k < end; ++k) left[split_list[k].prim] = 0;
    scratch.right_side.resize(end - begin);
    SweepRef* right = scratch.right_side.data();
    for (int axis = 0; axis < 3; ++axis) {
      if (axis == split_axis) continue;
      SweepRef* list = lists_[axis].data();
      // Branch-free (the side is unpredictable): every entry is written to both places and
      // only the cursor of its side advances. list[l] with l <= k was read already.
      size_t l = begin, r = 0;
      for (size_t k = begin; k < end; ++k) {
        const SweepRef entry = list[k];
        const size_t is_left = left[entry.prim];
        list[l] = entry;
        right[r] = entry;
        l += is_left;
        r += 1 - is_left;
      }
      ACCEL_CHECK(l == mid);
      std::copy(right, right + r, list + mid);
    }
  }

  /// Applies a sweep order to refs[begin, end).
  void apply_order(Scratch& scratch, const std::vector<uint32_t>& order, size_t begin) {
    scratch.refs.resize(order.size());
    for (size_t i = 0; i < order.size(); ++i) scratch.refs[i] = refs_[begin + order[i]];
    std::copy(scratch.refs.begin(), scratch.refs.end(), refs_.begin() + long(begin));
  }

  /// Lecture: "represent polygons by their midpoints, calculate the axis of largest extent
  /// using PCA, project the midpoints onto it and sort, search the minimum of C(B) by sweep".
  /// The axis changes per node, so this builder sorts per node.
  Split pca_split(Scratch& scratch, size_t begin, size_t end, const Aabb& box, [[maybe_unused]] int depth,
                  [[maybe_unused]] uint32_t id) {
    const size_t n = end - begin;
    DVec3 mean(0.0);
    for (size_t i = begin; i < end; ++i) mean += DVec3(refs_[i].centroid);
    mean /= double(n);
    glm::dmat3 cov(0.0);
    for (size_t i = begin; i < end; ++i) {
      const DVec3 d = DVec3(refs_[i].centroid) - mean;
      cov += glm::outerProduct(d, d);
    }
    // Dominant eigenvector by power iteration, started on the longest centroid axis.
    DVec3 axis(0.0);
    axis[centroid_bounds_of(refs_, begin, end).longest_axis()] = 1.0;
    for (int it = 0; it < 32; ++it) {
      const DVec3 next = cov * axis;
      const double len = glm::length(next);
      if (!(len > 0.0)) break;  // all centres equal: any axis will do
      axis = next / len;
    }
    std::vector<uint32_t>& order = scratch.order;
    std::vector<double>& key = scratch.key;
    order.resize(n);
    key.resize(n);
    for (size_t i = 0; i < n; ++i) key[i] = glm::dot(DVec3(refs_[begin + i].centroid), axis);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return key[a] < key[b] || (key[a] == key[b] && refs_[begin + a].prim < refs_[begin + b].prim);
    });
    if constexpr (Sink::kRecords) {
      if (sink_.records(depth)) {
        // The PCA direction is axis 3; the candidates lie along it, each halfway between two
        // consecutive projections of the sorted centres.
        sink_.axis(id, 3, Vec3(axis));
        scratch.rec_costs.resize(n);
        const Split s = sweep_order<true>(o_, refs_.data() + begin, order.data(), n, begin, box.area(),
                                          scratch.right_area, scratch.rec_costs.data());
        std::vector<SplitCandidate>& cands = scratch.rec_candidates;
        cands.resize(n - 1);
        for (size_t i = 1; i < n; ++i)
          cands[i - 1] = {float(0.5 * (key[order[i - 1]] + key[order[i]])), scratch.rec_costs[i], uint32_t(i),
                          uint32_t(n - i)};
        sink_.candidates(id, 3, cands.data(), cands.size());
        rec_axis_ = 3;
        rec_pos_ = cands[s.mid - begin - 1].pos;
        if (s.valid) apply_order(scratch, order, begin);
        return s;
      }
    }
    const Split s = sweep_order(o_, refs_.data() + begin, order.data(), n, begin, box.area(), scratch.right_area);
    if (s.valid) apply_order(scratch, order, begin);
    return s;
  }

  const BvhBuildOptions& o_;
  std::vector<PrimRef>& refs_;  ///< the median and PCA builders reorder it in place
  const size_t total_;
  std::vector<uint32_t> prims_;                        ///< the output's triangle list
  std::array<std::vector<SweepRef>, 3> lists_;  ///< SAH: per axis, each node's references in sorted order
  std::vector<uint8_t> left_;                    ///< SAH: per triangle, 1 = left side of its node's split
  std::vector<float> leaf_costs_;                ///< SAH: leaf_cost(k) for k = 0..N
  ProgressSpan* progress_;
  const std::thread::id reporter_;
  std::atomic<size_t> placed_{0};
  std::atomic<bool> stop_{false};
  Sink& sink_;
  // Recorded builds only: the split about to be recorded, the SAH lists' triangle -> refs_ index.
  int rec_axis_ = 0;
  float rec_pos_ = 0.0f;
  float rec_cost_ = 0.0f;
  std::vector<uint32_t> ref_of_prim_;
};

std::vector<PrimRef> make_refs(const Scene& scene) {
  std::vector<PrimRef> refs;
  refs.reserve(scene.valid_prims().size());
  for (uint32_t p : scene.valid_prims()) refs.push_back({scene.triangle_bounds(p), scene.centroid(p), p});
  return refs;
}

template <class Sink>
BuildTree build_top_down(const Scene& scene, const BvhBuildOptions& o, ProgressSpan* progress, Sink& sink) {
  sink.scene_box(scene.bounds());
  std::vector<PrimRef> refs = make_refs(scene);
  if (refs.empty()) return {};
  return TopDownBuilder<Sink>(o, refs, progress, sink).build();
}

// ============================================================================
// [SECTION] Collapse, depth limit and final layout for the bottom-up builders
// ============================================================================

/// A binary tree whose leaves hold exactly one triangle, as produced by clustering or
/// insertion. 32 bytes, aligned, so a node is one cache line access: insertion walks the
/// tree in random order, and its speed is the number of lines it touches.
struct alignas(32) BinaryNode {
  static constexpr uint32_t kLeaf = ~0u;
  Aabb box;
  uint32_t left = 0;   ///< inner: first child; leaf: kLeaf
  uint32_t right = 0;  ///< inner: second child; leaf: the triangle

  static BinaryNode leaf_of(const Aabb& box, uint32_t prim) { return {box, kLeaf, prim}; }
  static BinaryNode inner(const Aabb& box, uint32_t left, uint32_t right) { return {box, left, right}; }
  bool is_leaf() const { return left == kLeaf; }
  uint32_t prim() const { return right; }
};
static_assert(sizeof(BinaryNode) == 32);

/// Per node of a binary tree: subtree height (leaf = 0), triangle count, SAH cost, and
/// whether the subtree becomes one leaf (ci*n*A <= the subtree's cost, n <= leaf_size).
struct SubtreeCosts {
  std::vector<uint32_t> height, count;
  std::vector<float> cost;
  std::vector<uint8_t> collapse;
};

/// One post-order pass, without recursion (trees may be chains): everything the final
/// layout needs, and the heights limit_depth() needs, so the tree is walked once.
void compute_subtree_costs(const std::vector<BinaryNode>& nodes, uint32_t root, const BvhBuildOptions& o,
                           SubtreeCosts& c) {
  const size_t n = nodes.size();
  c.height.assign(n, 0);
  c.count.assign(n, 0);
  c.cost.assign(n, 0.0f);
  c.collapse.assign(n, 0);
  std::vector<std::pair<uint32_t, bool>> stack{{root, false}};
  while (!stack.empty()) {
    auto [i, expanded] = stack.back();
    stack.pop_back();
    const BinaryNode& nd = nodes[i];
    if (nd.is_leaf()) {
      c.count[i] = 1;
      c.cost[i] = o.leaf_cost(1) * nd.box.area();
      c.collapse[i] = 1;
    } else if (!expanded) {
      stack.push_back({i, true});
      stack.push_back({nd.left, false});
      stack.push_back({nd.right, false});
    } else {
      c.height[i] = 1 + std::max(c.height[nd.left], c.height[nd.right]);
      c.count[i] = c.count[nd.left] + c.count[nd.right];
      const float split_cost = o.ct * nd.box.area() + c.cost[nd.left] + c.cost[nd.right];
      const float leaf_cost = o.leaf_cost(c.count[i]) * nd.box.area();
      c.collapse[i] = c.count[i] <= uint32_t(o.leaf_size) && leaf_cost <= split_cost;
      c.cost[i] = c.collapse[i] ? leaf_cost : split_cost;
    }
  }
}

/// Triangles below node i, in tree order, appended to `out`; `stack` is scratch.
void gather_prims(const std::vector<BinaryNode>& nodes, uint32_t i, std::vector<uint32_t>& out,
                  std::vector<uint32_t>& stack) {
  stack.assign(1, i);
  while (!stack.empty()) {
    const uint32_t k = stack.back();
    stack.pop_back();
    if (nodes[k].is_leaf()) {
      out.push_back(nodes[k].prim());
    } else {
      stack.push_back(nodes[k].right);
      stack.push_back(nodes[k].left);
    }
  }
}

/// Balanced median-split subtree over prims[begin, end) (height ~ log2 n); returns its root.
/// The sink sees it as bottom-up steps: each triangle a cluster, each inner node a merge.
template <class Sink>
uint32_t build_median_binary(const Scene& scene, std::vector<BinaryNode>& nodes, std::vector<uint32_t>& prims,
                             size_t begin, size_t end, Sink& sink) {
  if (end - begin == 1) {
    nodes.push_back(BinaryNode::leaf_of(scene.triangle_bounds(prims[begin]), prims[begin]));
    const uint32_t id = uint32_t(nodes.size() - 1);
    if constexpr (Sink::kRecords) {
      Aabb centroid;
      centroid.extend(scene.centroid(prims[begin]));
      sink.node(id, kNoBuildNode, 0, nodes[id].box, centroid, &prims[begin], 1);
      sink.leaf(id, LeafReason::Cluster, &prims[begin], 1);
    }
    return id;
  }
  Aabb cb;
  for (size_t i = begin; i < end; ++i) cb.extend(scene.centroid(prims[i]));
  const int axis = cb.longest_axis();
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(prims.begin() + long(begin), prims.begin() + long(mid), prims.begin() + long(end),
                   [&](uint32_t a, uint32_t b) {
                     const float ca = scene.centroid(a)[axis], cb_ = scene.centroid(b)[axis];
                     return ca < cb_ || (ca == cb_ && a < b);
                   });
  const uint32_t l = build_median_binary(scene, nodes, prims, begin, mid, sink);
  const uint32_t r = build_median_binary(scene, nodes, prims, mid, end, sink);
  nodes.push_back(BinaryNode::inner(merge(nodes[l].box, nodes[r].box), l, r));
  const uint32_t id = uint32_t(nodes.size() - 1);
  if constexpr (Sink::kRecords) sink.merge(id, l, r, nodes[id].box, nodes[id].box.area());
  return id;
}

/// Depth bound of limit_depth(): trees up to 2 * kDepthCut high are left alone.
constexpr uint32_t kDepthCut = 32;
static_assert(2 * kDepthCut + 2 < uint32_t(kMaxBvhDepth));

/// Bounds the depth: an adversarial order (e.g. identical triangles) can make insertion
/// grow a chain. Every subtree hanging at depth kCut that is taller than kCut is rebuilt by
/// median split, so no leaf is deeper than about kCut + log2(n) + 1. `height` is the
/// subtree heights of the tree as it is. The sink sees each rebuilt subtree, then its
/// Replace step.
template <class Sink>
void limit_depth(const Scene& scene, std::vector<BinaryNode>& nodes, uint32_t root,
                 const std::vector<uint32_t>& height, Sink& sink) {
  constexpr uint32_t kCut = kDepthCut;
  std::vector<std::pair<uint32_t, uint32_t>> stack{{root, 0}};  // (node, depth)
  std::vector<uint32_t> prims, gather_stack;
  while (!stack.empty()) {
    auto [i, depth] = stack.back();
    stack.pop_back();
    if (nodes[i].is_leaf()) continue;
    for (int side = 0; side < 2; ++side) {
      const uint32_t child = side == 0 ? nodes[i].left : nodes[i].right;
      if (depth + 1 == kCut && height[child] > kCut) {
        prims.clear();
        gather_prims(nodes, child, prims, gather_stack);
        // build_median_binary appends to `nodes`: take no references across it.
        const uint32_t rebuilt = build_median_binary(scene, nodes, prims, 0, prims.size(), sink);
        sink.replace(rebuilt, child);
        (side == 0 ? nodes[i].left : nodes[i].right) = rebuilt;
      } else if (depth + 1 < kCut) {
        stack.push_back({child, depth + 1});
      }
    }
  }
}

/// Turns a single-triangle-leaf binary tree into a BuildTree: subtrees of at most
/// leaf_size triangles become one leaf when that is no more expensive by the SAH
/// (ci*n*A <= the subtree's cost), after bounding the depth.
/// Recorded builds: tree.event_ids maps every node to its binary node (the event ids), and
/// each inner node that becomes a leaf is recorded as a leaf step (the replay drops its children).
template <class Sink>
BuildTree finalize_binary_tree(const Scene& scene, std::vector<BinaryNode>& nodes, uint32_t root,
                               const BvhBuildOptions& o, Sink& sink) {
  SubtreeCosts costs;
  compute_subtree_costs(nodes, root, o, costs);
  if (costs.height[root] > 2 * kDepthCut) {  // rare: only then is the tree walked twice
    limit_depth(scene, nodes, root, costs.height, sink);
    compute_subtree_costs(nodes, root, o, costs);
  }
  const size_t n = nodes.size();
  const std::vector<uint32_t>& count = costs.count;
  const std::vector<uint8_t>& collapse = costs.collapse;
  BuildTree tree;
  tree.nodes.reserve(n);
  tree.prims.reserve(count[root]);
  struct Item {
    uint32_t src, dst;
  };
  tree.nodes.emplace_back();
  if constexpr (Sink::kRecords) tree.event_ids.resize(n);
  std::vector<Item> work{{root, 0}};
  std::vector<uint32_t> gather_stack;
  while (!work.empty()) {
    const Item it = work.back();
    work.pop_back();
    const BinaryNode& nd = nodes[it.src];
    tree.nodes[it.dst].box = nd.box;
    if constexpr (Sink::kRecords) tree.event_ids[it.dst] = it.src;
    if (collapse[it.src]) {
      tree.nodes[it.dst].first = uint32_t(tree.prims.size());
      gather_prims(nodes, it.src, tree.prims, gather_stack);
      tree.nodes[it.dst].count = uint32_t(tree.prims.size()) - tree.nodes[it.dst].first;
      if constexpr (Sink::kRecords)
        if (!nd.is_leaf())
          sink.leaf(it.src, LeafReason::NoGain, tree.prims.data() + tree.nodes[it.dst].first,
                    tree.nodes[it.dst].count);
      continue;
    }
    const uint32_t l = uint32_t(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.nodes.emplace_back();
    tree.nodes[it.dst].left = l;
    tree.nodes[it.dst].right = l + 1;
    work.push_back({nd.right, l + 1});
    work.push_back({nd.left, l});
  }
  if constexpr (Sink::kRecords) tree.event_ids.resize(tree.nodes.size());
  tree.root = 0;
  return tree;
}

// ============================================================================
// [SECTION] Bottom-up: locally-ordered clustering (PLOC, Meister & Bittner 2018)
// ============================================================================

/// Expands 10 bits to 30 by inserting two zeros between bits (Morton code helper).
uint32_t expand_bits(uint32_t v) {
  v = (v * 0x00010001u) & 0xFF0000FFu;
  v = (v * 0x00000101u) & 0x0F00F00Fu;
  v = (v * 0x00000011u) & 0xC30C30C3u;
  v = (v * 0x00000005u) & 0x49249249u;
  return v;
}

/// The nearest neighbour of every cluster within `radius` positions on each side of the
/// list: the one whose merged box has the least area, ties to the lower position (so the
/// answer does not depend on the order the candidates are seen in).
///
/// Each pair is measured once (the merged area is symmetric: merge(a, b) and merge(b, a)
/// differ at most in the sign of a zero, which compares equal) and offered to both ends.
/// Blocks of the list are independent tasks: a block measures its own pairs and those
/// reaching into it from the `radius` positions before it.
void nearest_neighbours(const std::vector<Aabb>& boxes, int radius, std::vector<uint32_t>& nearest) {
  const size_t n = boxes.size(), r = size_t(radius);
  constexpr size_t kBlock = 2048;
  nearest.resize(n);
  par::parallel_for(size_t(0), (n + kBlock - 1) / kBlock, [&](size_t block) {
    const size_t begin = block * kBlock, end = std::min(n, begin + kBlock);
    std::array<float, kBlock> best_area;
    std::array<uint32_t, kBlock> best;
    for (size_t i = begin; i < end; ++i) {
      best_area[i - begin] = kInf;
      best[i - begin] = uint32_t(i == 0 ? 1 : i - 1);
    }
    const auto offer = [&](size_t i, size_t j, float area) {
      float& a = best_area[i - begin];
      uint32_t& b = best[i - begin];
      if (area < a || (area == a && j < b)) {
        a = area;
        b = uint32_t(j);
      }
    };
    for (size_t i = begin >= r ? begin - r : 0; i < end; ++i) {
      const bool i_inside = i >= begin;
      const size_t j_begin = std::max(i + 1, begin);
      const size_t j_end = std::min(i_inside ? n : end, i + r + 1);
      for (size_t j = j_begin; j < j_end; ++j) {
        const float area = merge(boxes[i], boxes[j]).area();
        if (i_inside) offer(i, j, area);
        if (j < end) offer(j, i, area);
      }
    }
    std::copy(best.begin(), best.begin() + long(end - begin), nearest.begin() + long(begin));
  });
}

/// Records each triangle entering as a cluster: a parentless node that is a leaf.
template <class Sink>
void record_cluster(const Scene& scene, uint32_t id, const Aabb& box, uint32_t prim, Sink& sink) {
  Aabb centroid;
  centroid.extend(scene.centroid(prim));
  sink.node(id, kNoBuildNode, 0, box, centroid, &prim, 1);
  sink.leaf(id, LeafReason::Cluster, &prim, 1);
}

template <class Sink>
BuildTree build_bottom_up(const Scene& scene, const BvhBuildOptions& o, ProgressSpan* progress, Sink& sink) {
  sink.scene_box(scene.bounds());
  const auto& prims = scene.valid_prims();
  if (prims.empty()) return {};
  std::vector<BinaryNode> nodes;
  nodes.reserve(2 * prims.size());
  Aabb cb;
  for (uint32_t p : prims) cb.extend(scene.centroid(p));
  const Vec3 extent = glm::max(cb.extent(), Vec3(1e-30f));
  // Clusters start as single triangles ordered along a Morton curve, so spatial neighbours
  // are near each other in the list and the nearest-neighbour search can stay local.
  std::vector<std::pair<uint32_t, uint32_t>> keyed(prims.size());
  for (size_t i = 0; i < prims.size(); ++i) {
    const Vec3 q = glm::clamp((scene.centroid(prims[i]) - cb.min) / extent, Vec3(0.0f), Vec3(1.0f)) * 1023.0f;
    keyed[i] = {(expand_bits(uint32_t(q.x)) << 2) | (expand_bits(uint32_t(q.y)) << 1) | expand_bits(uint32_t(q.z)),
                prims[i]};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint32_t> clusters(prims.size());
  for (size_t i = 0; i < keyed.size(); ++i) {
    clusters[i] = uint32_t(nodes.size());
    nodes.push_back(BinaryNode::leaf_of(scene.triangle_bounds(keyed[i].second), keyed[i].second));
    if constexpr (Sink::kRecords) record_cluster(scene, clusters[i], nodes.back().box, keyed[i].second, sink);
  }
  constexpr int kRadius = 16;  // search window on each side (the paper uses 8..32)
  std::vector<Aabb> boxes;
  std::vector<uint32_t> nearest;
  std::vector<uint32_t> next;
  while (clusters.size() > 1) {
    const size_t n = clusters.size();
    boxes.resize(n);
    for (size_t i = 0; i < n; ++i) boxes[i] = nodes[clusters[i]].box;  // read 2 * kRadius times each
    nearest_neighbours(boxes, kRadius, nearest);
    // Merge mutual nearest neighbours; keep the merged cluster at the lower position so the
    // list stays in Morton order.
    next.clear();
    bool merged_any = false;
    for (size_t i = 0; i < n; ++i) {
      const uint32_t j = nearest[i];
      if (nearest[j] == i) {
        if (i < j) {
          const uint32_t a = clusters[i], b = clusters[j];
          nodes.push_back(BinaryNode::inner(merge(nodes[a].box, nodes[b].box), a, b));
          next.push_back(uint32_t(nodes.size() - 1));
          merged_any = true;
          if constexpr (Sink::kRecords) sink.merge(next.back(), a, b, nodes.back().box, nodes.back().box.area());
        }
        continue;  // j > i was merged into i
      }
      next.push_back(clusters[i]);
    }
    if (!merged_any) {  // cannot happen (the globally closest pair is mutual), but never loop forever
      const uint32_t a = next[0], b = next[1];
      nodes.push_back(BinaryNode::inner(merge(nodes[a].box, nodes[b].box), a, b));
      if constexpr (Sink::kRecords)
        sink.merge(uint32_t(nodes.size() - 1), a, b, nodes.back().box, nodes.back().box.area());
      next.erase(next.begin(), next.begin() + 2);
      next.insert(next.begin(), uint32_t(nodes.size() - 1));
    }
    clusters.swap(next);
    // Progress: merges done (n - 1 in all) per round; the rounds shrink geometrically.
    if (progress && !progress->advance(double(prims.size() - clusters.size()) / double(prims.size()))) return {};
  }
  return finalize_binary_tree(scene, nodes, clusters[0], o, sink);
}

// ============================================================================
// [SECTION] Insertion (Goldsmith & Salmon 1987)
// ============================================================================

template <class Sink>
BuildTree build_insertion(const Scene& scene, const BvhBuildOptions& o, ProgressSpan* progress, Sink& sink) {
  sink.scene_box(scene.bounds());
  std::vector<uint32_t> order = scene.valid_prims();
  if (order.empty()) return {};
  // Goldsmith & Salmon recommend a random insertion order: file order is spatially coherent
  // and grows lopsided trees. A seeded shuffle keeps the build deterministic.
  Rng rng(0x5eed);
  for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.next_u64() % i]);

  std::vector<BinaryNode> nodes;
  nodes.reserve(2 * order.size());
  constexpr uint32_t kNone = ~0u;
  constexpr size_t kProgressBatch = 1024;  // triangles inserted between progress reports
  uint32_t root = kNone;
  for (size_t inserted = 0; inserted < order.size(); ++inserted) {
    if (progress && inserted % kProgressBatch == 0 && !progress->advance(double(inserted) / double(order.size())))
      return {};
    const uint32_t prim = order[inserted];
    // The shuffled order reads the triangle boxes at random: fetch a few ahead.
    constexpr size_t kAhead = 8;
    if (inserted + kAhead < order.size())
      _mm_prefetch(reinterpret_cast<const char*>(&scene.triangle_bounds(order[inserted + kAhead])), _MM_HINT_T0);
    const Aabb box = scene.triangle_bounds(prim);
    const uint32_t leaf = uint32_t(nodes.size());
    nodes.push_back(BinaryNode::leaf_of(box, prim));
    if constexpr (Sink::kRecords) record_cluster(scene, leaf, box, prim, sink);
    if (root == kNone) {
      root = leaf;
      continue;
    }
    // Sift down: at each node, either make the new triangle its sibling (cost: the area of
    // the new parent) or descend into the child whose area grows least. Every ancestor's
    // area grows too (the inherited cost), which is what makes this the SAH-greedy choice.
    // A node we descend from becomes an ancestor of the new triangle, so its box is
    // refitted right then, while it is in cache (its old box was read already; nothing
    // further down reads it).
    uint32_t at = root, above = kNone;
    float inherited = 0.0f;
    [[maybe_unused]] int depth = 0;  // recorded builds: the depth of `at`
    while (!nodes[at].is_leaf()) {
      const BinaryNode& node = nodes[at];
      const BinaryNode &l = nodes[node.left], &r = nodes[node.right];
      // The next level's nodes load while this one is decided.
      if (!l.is_leaf()) {
        _mm_prefetch(reinterpret_cast<const char*>(&nodes[l.left]), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(&nodes[l.right]), _MM_HINT_T0);
      }
      if (!r.is_leaf()) {
        _mm_prefetch(reinterpret_cast<const char*>(&nodes[r.left]), _MM_HINT_T0);
        _mm_prefetch(reinterpret_cast<const char*>(&nodes[r.right]), _MM_HINT_T0);
      }
      const float combined = merge(node.box, box).area();
      const float here = combined + inherited;
      const float grow = inherited + combined - node.box.area();
      auto child_cost = [&](const BinaryNode& c) {
        const float a = merge(c.box, box).area();
        return c.is_leaf() ? a + grow : a - c.box.area() + grow;
      };
      const float cl = child_cost(l), cr = child_cost(r);
      if constexpr (Sink::kRecords) {
        const float costs[3] = {here, cl, cr};
        const int choice = here <= cl && here <= cr ? 0 : cl <= cr ? 1 : 2;
        // The node grows only when the triangle goes on below it; as the sibling here, the
        // triangle is bounded by the new parent instead (the merge step), the node keeps its box.
        sink.insert_step(prim, at, depth, choice == 0 ? node.box : merge(node.box, box), costs, choice);
        ++depth;
      }
      if (here <= cl && here <= cr) break;
      inherited = grow;
      nodes[at].box.extend(box);
      above = at;
      at = cl <= cr ? node.left : node.right;
    }
    // New inner node replaces `at`, with children `at` and the new leaf.
    const uint32_t inner = uint32_t(nodes.size());
    nodes.push_back(BinaryNode::inner(merge(nodes[at].box, box), at, leaf));
    if constexpr (Sink::kRecords) sink.merge(inner, at, leaf, nodes.back().box, nodes.back().box.area());
    if (above == kNone) {
      root = inner;
    } else if (nodes[above].left == at) {
      nodes[above].left = inner;
    } else {
      nodes[above].right = inner;
    }
  }
  return finalize_binary_tree(scene, nodes, root, o, sink);
}

}  // namespace

BuildTree build_bvh_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                         BuildRecorder* recorder) {
  if (options.builder == BvhBuilderKind::BinnedSah) return build_binned_sah_tree(scene, options, progress, recorder);
  if (options.builder == BvhBuilderKind::Sbvh) return build_spatial_split_tree(scene, options, progress, recorder);
  const auto run = [&](auto& sink) {
    switch (options.builder) {
      case BvhBuilderKind::BottomUp: return build_bottom_up(scene, options, progress, sink);
      case BvhBuilderKind::Insertion: return build_insertion(scene, options, progress, sink);
      default: return build_top_down(scene, options, progress, sink);
    }
  };
  if (recorder) return run(*recorder);
  NullBuildSink no_steps;
  return run(no_steps);
}

}  // namespace accel
