// SAH plane sweep (lecture, "in case the intended application is known: use a cost function;
// try all 3 axes, search for the minimum along each axis, choose the axis and position with
// the smallest minimum"), after MacDonald & Booth 1990, "Heuristics for ray tracing using
// space subdivision". The recursion and its tasks are bvh_top_down.h's.
//
// The sweep sorts once: the references are sorted by centre on each axis at the root, and
// each node's three sorted lists are split by stable partitioning (a flag per reference
// marks the left side), so a node of n references costs O(n) instead of three sorts. The
// order on an axis is a total order (centroid_less), so a node's list is exactly what
// sorting its references would give, and the splits, costs and leaf orders are those of
// sorting per node.
#include "structures/bvh_sweep_builder.h"

#include <emmintrin.h>  // SSE2: part of every x86-64 CPU (as in geometry.h)

#include <array>

#include "bit_cast.h"
#include "radix_sort.h"
#include "structures/bvh_top_down.h"

namespace accel {
namespace {

using namespace top_down;

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

/// Splits a node by the SAH sweep over its three sorted axis lists.
template <class Sink>
class SweepSplitter : public RefRangeSplitter<SweepSplitter<Sink>, Sink> {
 public:
  static constexpr bool kSahLeafRule = true;
  struct Scratch : ScratchBase {
    std::vector<float> right_area;
    std::vector<SweepRef> right_side;
  };

  // refs_ stays in scene order; the sorted lists move.
  SweepSplitter(const Scene& scene, const BvhBuildOptions& o, Sink& sink)
      : RefRangeSplitter<SweepSplitter<Sink>, Sink>(scene, o, sink), total_(refs_.size()) {}

  /// The node's box, scanned in the order its references arrive in.
  Aabb bounds(int order, size_t begin, size_t end) const {
    if (order == kRefsOrder) return bounds_of(refs_, begin, end);
    SweepBox b;
    for (size_t i = begin; i < end; ++i) b.extend(lists_[order][i]);
    return b.aabb();
  }
  uint32_t prim(int order, size_t k) const { return order == kRefsOrder ? refs_[k].prim : lists_[order][k].prim; }
  const Vec3& centroid(int order, size_t k) const {
    return order == kRefsOrder ? refs_[k].centroid : centroid_of_prim(lists_[order][k].prim);
  }

  /// The root, after its three sorted lists are made. A node owns the same range
  /// [begin, end) of all three (the children get its two halves), so tasks never touch the
  /// same entries.
  RefRange root() {
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
      radix_sort_stable<32, 11>(keys, scratch, [](uint64_t v) { return v >> 32; });
      std::vector<SweepRef>& list = lists_[axis];
      list.resize(total_);
      par::parallel_for(size_t(0), total_, [&](size_t i) {
        const uint32_t ref = uint32_t(keys[i]);
        const Aabb& b = refs_[ref].box;
        list[i] = {{b.min.x, b.min.y, b.min.z}, refs_[ref].prim, {b.max.x, b.max.y, b.max.z}};
      });
    });
    return {0, total_, kRefsOrder};
  }

  /// Lecture: "try all 3 axes, search for the minimum along each axis, choose the smallest".
  /// This is the PCA builder's sweep_order() (bvh_pca_builder.cpp) on each axis list, the
  /// three sweeps interleaved (independent dependency chains, so the CPU overlaps them), with
  /// the boxes read in place and the leaf costs from a table (the same floats as
  /// leaf_cost(), without its division). As there, the first minimum of an axis wins, and
  /// on equal costs the lower axis.
  Split split(Scratch& scratch, RefRange& w, const Aabb& box, [[maybe_unused]] int depth,
              [[maybe_unused]] uint32_t id) {
    const size_t begin = w.begin, n = w.end - w.begin;  // n >= 2
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
    Split s{true, begin + best_i[winner], best_cost[winner], winner};
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
      sink_.axis(id, winner, unit_axis(winner));
      const size_t i = best_i[winner];
      s.plane_axis = winner;
      s.plane_pos = 0.5f * (centroid_of_prim(list[winner][i - 1].prim)[winner] +
                           centroid_of_prim(list[winner][i].prim)[winner]);
    }
    return s;
  }

  /// After the split: the children's sorted lists (partition_axis_lists()). The sweep's
  /// split is always inside the node (it tries every position).
  void partition(Scratch& scratch, RefRange& w, Split& split, RefRange& left, RefRange& right, int, uint32_t id,
                 float leaf_cost) {
    ACCEL_CHECK(split.valid && split.mid > w.begin && split.mid < w.end);
    this->children(w, split, left, right, id, leaf_cost);
    partition_axis_lists(scratch, split.child_order, w.begin, split.mid, w.end);
  }

 private:
  /// The centre of a triangle of the lists (refs_ stays in scene order).
  const Vec3& centroid_of_prim(uint32_t prim) const { return refs_[ref_of_prim_[prim]].centroid; }

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

  using RefRangeSplitter<SweepSplitter<Sink>, Sink>::o_;
  using RefRangeSplitter<SweepSplitter<Sink>, Sink>::sink_;
  using RefRangeSplitter<SweepSplitter<Sink>, Sink>::refs_;
  const size_t total_;
  std::array<std::vector<SweepRef>, 3> lists_;  ///< per axis, each node's references in sorted order
  std::vector<uint8_t> left_;                   ///< per triangle, 1 = left side of its node's split
  std::vector<float> leaf_costs_;               ///< leaf_cost(k) for k = 0..N
  std::vector<uint32_t> ref_of_prim_;           ///< recorded builds: triangle -> refs_ index
};

}  // namespace

BuildTree build_sweep_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                           BuildRecorder* recorder) {
  return build_top_down<SweepSplitter>(scene, options, progress, recorder);
}

}  // namespace accel
