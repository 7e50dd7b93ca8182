#pragma once
// The binned SAH object split of the binned builder's splitter (bvh_binned_builder.cpp),
// shared with the spatial-split builder's (bvh_spatial_builder.cpp): the 32-byte
// references, the SSE bins and sweep, the in-place partition and the median fallback. The
// recursion is bvh_top_down.h's. Not a public interface: only these two builders include it.
#include <emmintrin.h>  // SSE2: part of every x86-64 CPU (as in geometry.h)

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <vector>

#include "bit_cast.h"
#include "build_control.h"
#include "check.h"
#include "geometry.h"
#include "parallel.h"
#include "structures/bvh_build_types.h"
#include "structures/bvh_top_down.h"

namespace accel::binned {

constexpr int kMaxBins = 256;                  // upper bound of the `bins` parameter
constexpr size_t kParallelBinThreshold = 1u << 16;  // larger nodes bin in parallel ...
constexpr size_t kBinSlice = 1u << 14;         // ... over slices of this many references
constexpr size_t kDualBinThreshold = 64;       // larger ranges bin into two sets (bin_refs)

/// A triangle reference: its box, with the triangle index in the spare lane of `lo`.
/// Two aligned SSE loads give the box (Wald 2007 uses the same compact layout).
struct alignas(16) Ref {
  float lo[3];
  uint32_t prim;
  float hi[3];
  float pad;
};
static_assert(sizeof(Ref) == 32);

/// Clears lane 3 (the triangle index of `lo`), which must never enter float arithmetic
/// (as a float it is a denormal, which is slow, and meaningless).
inline __m128 xyz_mask() { return _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1)); }
inline __m128 load_lo(const Ref& r, __m128 mask) { return _mm_and_ps(_mm_load_ps(r.lo), mask); }
inline __m128 load_hi(const Ref& r) { return _mm_load_ps(r.hi); }

/// Box as two SSE registers; lane 3 is unused. Starts empty.
struct Box4 {
  __m128 lo = _mm_set1_ps(kInf);
  __m128 hi = _mm_set1_ps(-kInf);
  void extend(__m128 l, __m128 h) {
    lo = _mm_min_ps(lo, l);
    hi = _mm_max_ps(hi, h);
  }
  void extend(const Box4& b) { extend(b.lo, b.hi); }
  /// Surface area, computed as Aabb::area() does (the box must not be empty).
  float area() const {
    alignas(16) float e[4];
    _mm_store_ps(e, _mm_sub_ps(hi, lo));
    return 2.0f * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]);
  }
  Aabb aabb() const { return aabb_from_lanes(lo, hi); }
};

/// A node's references refs[begin, end) with their bounds, as the parent's partition found them.
struct Range {
  size_t begin = 0, end = 0;
  Box4 box;       ///< union of the triangle boxes (the node's box)
  Box4 centroid;  ///< bounds of the doubled centroids lo + hi
  size_t size() const { return end - begin; }
  /// The centroid bounds in scene units (the references hold twice the centroid, lo + hi).
  Aabb centroid_bounds() const {
    Aabb c = centroid.aabb();
    c.min *= 0.5f;
    c.max *= 0.5f;
    return c;
  }
};

/// A bin's box; trivially constructible, so a BinSet is not initialised beyond the bins in use.
struct BinBox {
  __m128 lo, hi;
};

/// Per-axis bins of one node: boxes per axis, and the counts of bin b on the three axes in
/// one row (lane 3 unused), so that the sweep handles the three axes as SSE lanes.
struct BinSet {
  BinBox box[3][kMaxBins];
  alignas(16) uint32_t count[kMaxBins][4];
  void clear(int nb) {
    const BinBox empty{_mm_set1_ps(kInf), _mm_set1_ps(-kInf)};
    for (int a = 0; a < 3; ++a) std::fill(box[a], box[a] + nb, empty);
    for (int b = 0; b < nb; ++b) std::fill(count[b], count[b] + 4, 0u);
  }
  void add(int a, int b, __m128 lo, __m128 hi) {
    box[a][b].lo = _mm_min_ps(box[a][b].lo, lo);
    box[a][b].hi = _mm_max_ps(box[a][b].hi, hi);
    ++count[b][a];
  }
  __m128i counts(int b) const { return _mm_load_si128(reinterpret_cast<const __m128i*>(count[b])); }
  void merge(const BinSet& o, int nb) {
    for (int b = 0; b < nb; ++b) {
      for (int a = 0; a < 3; ++a) {
        box[a][b].lo = _mm_min_ps(box[a][b].lo, o.box[a][b].lo);
        box[a][b].hi = _mm_max_ps(box[a][b].hi, o.box[a][b].hi);
      }
      _mm_store_si128(reinterpret_cast<__m128i*>(count[b]), _mm_add_epi32(counts(b), o.counts(b)));
    }
  }
};

/// Three boxes being grown, one per axis: after a transpose, their areas are one SSE vector.
struct AxisBoxes {
  __m128 lo[3] = {_mm_set1_ps(kInf), _mm_set1_ps(kInf), _mm_set1_ps(kInf)};
  __m128 hi[3] = {_mm_set1_ps(-kInf), _mm_set1_ps(-kInf), _mm_set1_ps(-kInf)};
  void extend(const BinSet& bins, int b) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = _mm_min_ps(lo[a], bins.box[a][b].lo);
      hi[a] = _mm_max_ps(hi[a], bins.box[a][b].hi);
    }
  }
  /// Lane a: the area of box a, as Aabb::area() computes it (garbage for an empty box).
  __m128 areas() const {
    __m128 x = _mm_sub_ps(hi[0], lo[0]), y = _mm_sub_ps(hi[1], lo[1]), z = _mm_sub_ps(hi[2], lo[2]);
    __m128 w = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(x, y, z, w);  // now x holds the x extents of the three boxes, etc.
    const __m128 sum = _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, y), _mm_mul_ps(y, z)), _mm_mul_ps(z, x));
    return _mm_mul_ps(_mm_set1_ps(2.0f), sum);
  }
};

inline __m128 select(__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); }

/// Maps a doubled centroid to its bin on each axis: floor((c - lo) * scale), clamped to
/// [0, nb - 1] (in floats, because SSE2 has no integer min/max). Binning and partition both
/// call this, so a reference is always classified the same way.
struct BinMap {
  __m128 lo, scale, top;
  __m128i bins(__m128 c) const {
    const __m128 f = _mm_min_ps(_mm_max_ps(_mm_mul_ps(_mm_sub_ps(c, lo), scale), _mm_setzero_ps()), top);
    return _mm_cvttps_epi32(f);
  }
};

/// The chosen plane: left are the references whose bin on `axis` (by `map`) is below `bin`.
struct BinSplit {
  bool valid = false;
  int axis = -1, bin = 0;
  float cost = 0.0f;
  BinMap map{};  ///< the node's bin map, which partition() classifies by
};

/// Per-task buffers of the binned split, allocated once per task, not per node, and off the
/// stack: a BinSet is 27 KB and the recursion may be 96 deep. Left uninitialised (every
/// node clears the bins it uses and the sweep writes before it reads): zeroing the 64 KB of
/// each of the few hundred tasks was 2% of a build's instructions.
struct Scratch : top_down::ScratchBase {
  // `new T` without parentheses: default-initialised (make_unique_for_overwrite, which the
  // web build's libc++ lacks).
  std::unique_ptr<BinSet> bins{new BinSet};
  std::unique_ptr<BinSet> spare{new BinSet};
  struct RightSweep {
    __m128 area[kMaxBins];    ///< lane a: area of the bins >= b on axis a
    __m128i count[kMaxBins];  ///< lane a: references in the bins >= b on axis a
  };
  std::unique_ptr<RightSweep> right{new RightSweep};
  std::vector<SplitCandidate> planes[3];  ///< recording only: the planes of the node being swept
};

/// The binned object split of a node's references refs[r.begin, r.end), over a build sink
/// (build_trace.h): NullBuildSink for the normal build, BuildRecorder for the recorded one.
/// Stateless between nodes (the state of a node is in its Range, BinSplit and Scratch), so
/// one serves every task.
template <class Sink>
class BinnedSah {
 public:
  BinnedSah(const BvhBuildOptions& o, Sink& sink) : o_(o), sink_(sink) {
    const uint32_t ppt = uint32_t(o.prims_per_test);
    if (ppt > 0 && (ppt & (ppt - 1)) == 0) ppt_shift_ = std::countr_zero(ppt);
  }

  /// Splits the node `r` of `refs` into `left` and `right` by `split` (the binned plane),
  /// or by the object median when there is no binned split, and records the Split step.
  /// `partitioned`: refs is already partitioned by `split` into `left` and `right`.
  void split_objects(Ref* refs, const Range& r, const BinSplit& split, bool partitioned, Range& left, Range& right,
                     [[maybe_unused]] uint32_t id, [[maybe_unused]] float leaf_cost) const {
    const bool binned = split.valid && (partitioned || partition(refs, r, split, left, right));
    if (!binned) median_split(refs, r, left, right);
    if constexpr (Sink::kRecords) {
      if (binned) {
        sink_.split(id, split.axis, split_position(split), split.cost, leaf_cost, uint32_t(left.size()),
                    uint32_t(right.size()), 0);
      } else {  // the object median: no cost computed
        const int axis = r.centroid.aabb().longest_axis();
        sink_.axis(id, axis, Vec3(0.0f));
        sink_.split(id, axis, 0.5f * (refs[left.end - 1].lo[axis] + refs[left.end - 1].hi[axis]), std::nanf(""),
                    leaf_cost, uint32_t(left.size()), uint32_t(right.size()), 0);
      }
    }
  }

 private:
  /// Bin count for a node of n references: `bins` at most, 4 + n / 4 below that. A node's
  /// clearing and sweep cost ~80 instructions a bin against ~45 a reference to bin, so with
  /// a bin per two references (as before issue #51) the sweep cost nodes of a few hundred
  /// references more than their binning. A bin per four moved the SAH cost by +0.2% in
  /// geometric mean over the shared meshes (-0.6% to +3.9%) and took 6-10% off the build
  /// (docs/performance.md).
  int bin_count(size_t n) const { return int(std::min<size_t>(size_t(std::min(o_.bins, kMaxBins)), 4 + n / 4)); }

  /// o_.leaf_cost(n), with a shift instead of the integer division for the usual power-of-two
  /// prims_per_test (the division was a tenth of the whole build in a profile).
  float leaf_cost(uint32_t n) const {
    if (ppt_shift_ < 0) return o_.leaf_cost(n);
    return o_.ci * float((n + (1u << ppt_shift_) - 1) >> ppt_shift_);
  }

  /// leaf_cost() of each lane's count.
  __m128 leaf_costs(__m128i n) const {
    if (ppt_shift_ < 0) {
      alignas(16) uint32_t c[4];
      _mm_store_si128(reinterpret_cast<__m128i*>(c), n);
      return _mm_set_ps(0.0f, leaf_cost(c[2]), leaf_cost(c[1]), leaf_cost(c[0]));
    }
    const __m128i rounded = _mm_add_epi32(n, _mm_set1_epi32((1 << ppt_shift_) - 1));
    return _mm_mul_ps(_mm_set1_ps(o_.ci), _mm_cvtepi32_ps(_mm_srl_epi32(rounded, _mm_cvtsi32_si128(ppt_shift_))));
  }

  /// Where the plane between bins b - 1 and b lies on `axis`, in scene units (the map bins
  /// twice the centroid).
  static float plane_position(const BinMap& map, int axis, int b) {
    alignas(16) float lo[4], scale[4];
    _mm_store_ps(lo, map.lo);
    _mm_store_ps(scale, map.scale);
    return 0.5f * (lo[axis] + float(b) / scale[axis]);
  }

  BinMap bin_map(const Range& r, int nb, bool* any_extent) const {
    alignas(16) float lo[4], hi[4], scale[4] = {0, 0, 0, 0};
    _mm_store_ps(lo, r.centroid.lo);
    _mm_store_ps(hi, r.centroid.hi);
    *any_extent = false;
    for (int a = 0; a < 3; ++a) {
      const float extent = hi[a] - lo[a];
      if (extent > 0.0f) {
        scale[a] = float(nb) / extent;
        *any_extent = true;
      }
    }
    return {r.centroid.lo, _mm_load_ps(scale), _mm_set1_ps(float(nb - 1))};
  }

  /// Bins refs[begin, end) on all three axes in one pass (Wald 2007, section 3.2).
  /// Neighbouring references usually fall into the same bin, so binning into one set makes
  /// every update wait for the previous one's store; large ranges therefore alternate
  /// between `bins` and `spare` (merged at the end: min/max and counts are exact in any
  /// order), which halves that chain.
  static void bin_refs(const Ref* refs, size_t begin, size_t end, const BinMap& map, int nb, BinSet& bins,
                       BinSet& spare) {
    const __m128 mask = xyz_mask();
    alignas(16) int32_t idx[4], idx2[4];
    size_t i = begin;
    if (end - begin >= kDualBinThreshold) {
      spare.clear(nb);
      for (; i + 1 < end; i += 2) {
        const __m128 lo = load_lo(refs[i], mask), hi = load_hi(refs[i]);
        const __m128 lo2 = load_lo(refs[i + 1], mask), hi2 = load_hi(refs[i + 1]);
        _mm_store_si128(reinterpret_cast<__m128i*>(idx), map.bins(_mm_add_ps(lo, hi)));
        _mm_store_si128(reinterpret_cast<__m128i*>(idx2), map.bins(_mm_add_ps(lo2, hi2)));
        for (int a = 0; a < 3; ++a) {
          bins.add(a, idx[a], lo, hi);
          spare.add(a, idx2[a], lo2, hi2);
        }
      }
      bins.merge(spare, nb);
    }
    for (; i < end; ++i) {
      const __m128 lo = load_lo(refs[i], mask), hi = load_hi(refs[i]);
      _mm_store_si128(reinterpret_cast<__m128i*>(idx), map.bins(_mm_add_ps(lo, hi)));
      for (int a = 0; a < 3; ++a) bins.add(a, idx[a], lo, hi);
    }
  }

 public:  // the object split, also used by the spatial-split builder (bvh_spatial_builder.cpp)
  /// Where the plane of `split` lies, in scene units.
  static float split_position(const BinSplit& split) { return plane_position(split.map, split.axis, split.bin); }

  /// The cheapest binned plane on any axis by the SAH; ties keep the lower axis and plane.
  /// `depth`, `id`: the node's, for the recorded Candidates steps.
  BinSplit find_split(Scratch& scratch, const Ref* refs, const Range& r, int depth, uint32_t id) const {
    const size_t n = r.size();
    const int nb = bin_count(n);
    bool any_extent = false;
    const BinMap map = bin_map(r, nb, &any_extent);
    BinSplit best;
    if (!any_extent) return best;  // all centroids equal: the caller falls back to the median
    BinSet& bins = *scratch.bins;
    bins.clear(nb);
    if (n >= kParallelBinThreshold) {
      // Fixed slices, merged in slice order: the bins do not depend on the scheduling.
      const size_t slices = (n + kBinSlice - 1) / kBinSlice;
      const std::unique_ptr<BinSet[]> partial(new BinSet[slices]);  // default-initialised: no 27 KB memset each
      par::parallel_for(size_t(0), slices, [&](size_t s) {
        partial[s].clear(nb);
        BinSet spare;  // uninitialised: bin_refs clears what it uses
        bin_refs(refs, r.begin + s * kBinSlice, std::min(r.end, r.begin + (s + 1) * kBinSlice), map, nb, partial[s],
                 spare);
      });
      for (size_t s = 0; s < slices; ++s) bins.merge(partial[s], nb);
    } else {
      bin_refs(refs, r.begin, r.end, map, nb, bins, *scratch.spare);
    }
    return sweep(scratch, nb, r, map, depth, id);
  }

  /// SAH sweep over the bins (Wald 2007, section 3.2), the three axes side by side in SSE
  /// lanes. Per lane it is the scalar sweep: the cost formula of sah_split_cost() in
  /// bvh_builders.cpp in the same operation order, the first (lowest) plane kept on ties,
  /// then the lowest axis among equal costs, as a loop over axes then planes would choose.
  BinSplit sweep(Scratch& scratch, int nb, const Range& r, const BinMap& map, [[maybe_unused]] int depth,
                 [[maybe_unused]] uint32_t id) const {
    const BinSet& bins = *scratch.bins;
    const __m128 axis_ok = _mm_cmpgt_ps(_mm_sub_ps(r.centroid.hi, r.centroid.lo), _mm_setzero_ps());
    const float parent_area = r.box.area();
    const __m128 inv = _mm_set1_ps(parent_area > 0.0f ? 1.0f / parent_area : 1.0f);
    const __m128 ct = _mm_set1_ps(o_.ct);
    __m128* right_area = scratch.right->area;
    __m128i* right_count = scratch.right->count;
    AxisBoxes acc;
    __m128i cnt = _mm_setzero_si128();
    for (int b = nb - 1; b > 0; --b) {
      acc.extend(bins, b);
      cnt = _mm_add_epi32(cnt, bins.counts(b));
      right_area[b] = acc.areas();
      right_count[b] = cnt;
    }
    acc = AxisBoxes{};
    cnt = _mm_setzero_si128();
    __m128 best_cost = _mm_set1_ps(kInf), best_valid = _mm_setzero_ps();
    __m128i best_bin = _mm_setzero_si128();
    for (int b = 1; b < nb; ++b) {  // plane between bin b - 1 and bin b
      acc.extend(bins, b - 1);
      cnt = _mm_add_epi32(cnt, bins.counts(b - 1));
      const __m128 valid = _mm_and_ps(
          axis_ok, _mm_castsi128_ps(_mm_and_si128(_mm_cmpgt_epi32(cnt, _mm_setzero_si128()),
                                                  _mm_cmpgt_epi32(right_count[b], _mm_setzero_si128()))));
      const __m128 cost =
          _mm_add_ps(ct, _mm_mul_ps(_mm_add_ps(_mm_mul_ps(acc.areas(), leaf_costs(cnt)),
                                               _mm_mul_ps(right_area[b], leaf_costs(right_count[b]))),
                                    inv));
      const __m128 take = _mm_and_ps(valid, _mm_or_ps(_mm_cmplt_ps(cost, best_cost), _mm_andnot_ps(best_valid, valid)));
      best_cost = select(take, cost, best_cost);
      best_bin = _mm_castps_si128(select(take, _mm_castsi128_ps(_mm_set1_epi32(b)), _mm_castsi128_ps(best_bin)));
      best_valid = _mm_or_ps(best_valid, valid);
      if constexpr (Sink::kRecords) record_plane(scratch, b, valid, cost, cnt, right_count[b]);
    }
    if constexpr (Sink::kRecords) record_candidates(scratch, id, map, depth);
    alignas(16) float costs[4];
    alignas(16) int32_t bin[4], ok[4];
    _mm_store_ps(costs, best_cost);
    _mm_store_si128(reinterpret_cast<__m128i*>(bin), best_bin);
    _mm_store_si128(reinterpret_cast<__m128i*>(ok), _mm_castps_si128(best_valid));
    BinSplit best;
    for (int a = 0; a < 3; ++a)
      if (ok[a] && (!best.valid || costs[a] < best.cost)) best = {true, a, bin[a], costs[a], map};
    return best;
  }

  /// In-place two-pointer partition by the chosen plane; accumulates the children's boxes
  /// and centroid bounds on the way (Wald 2007: no second pass over the references).
  /// Only the split axis is classified, with the scalar form of BinMap::bins() (the same
  /// float operations, so a reference goes to the side its bin says), and the four bounds
  /// live in registers, not in the Ranges. False if a side came out empty (cannot happen
  /// for a plane the binning found).
  static bool partition(Ref* refs, const Range& r, const BinSplit& split, Range& left, Range& right) {
    const __m128 mask = xyz_mask();
    alignas(16) float map_lo[4], map_scale[4];
    _mm_store_ps(map_lo, split.map.lo);
    _mm_store_ps(map_scale, split.map.scale);
    const int axis = split.axis;
    const float lo_a = map_lo[axis], scale_a = map_scale[axis], top = _mm_cvtss_f32(split.map.top);
    const int split_bin = split.bin;
    auto goes_left = [&](const Ref& ref) {
      const float c = ref.lo[axis] + ref.hi[axis];
      const float f = (c - lo_a) * scale_a;
      const float clamped_low = f > 0.0f ? f : 0.0f;  // _mm_max_ps(f, 0), NaN included
      return int(clamped_low < top ? clamped_low : top) < split_bin;  // _mm_min_ps, truncation

    };
    Box4 lbox, lcen, rbox, rcen;
    auto add = [mask](const Ref& ref, Box4& box, Box4& cen) {
      const __m128 lo = load_lo(ref, mask), hi = load_hi(ref), c = _mm_add_ps(lo, hi);
      box.extend(lo, hi);
      cen.extend(c, c);
    };
    size_t i = r.begin, j = r.end;
    while (true) {
      while (i < j && goes_left(refs[i])) add(refs[i++], lbox, lcen);
      while (i < j && !goes_left(refs[j - 1])) add(refs[--j], rbox, rcen);
      if (i >= j) break;
      // refs[i] goes right and refs[j - 1] goes left.
      std::swap(refs[i], refs[j - 1]);
      add(refs[i++], lbox, lcen);
      add(refs[--j], rbox, rcen);
    }
    left = Range{};
    right = Range{};
    left.box = lbox;
    left.centroid = lcen;
    right.box = rbox;
    right.centroid = rcen;
    left.begin = r.begin;
    left.end = right.begin = i;
    right.end = r.end;
    return left.size() > 0 && right.size() > 0;
  }

  /// Fallback: object median along the longest centroid axis, ties by triangle index, as
  /// object_median_split() in bvh_builders.cpp (always valid for >= 2 references).
  static void median_split(Ref* refs, const Range& r, Range& left, Range& right) {
    const Aabb cb = r.centroid.aabb();
    const int axis = cb.longest_axis();
    const size_t mid = r.begin + r.size() / 2;
    std::nth_element(refs + r.begin, refs + mid, refs + r.end, [axis](const Ref& a, const Ref& b) {
      const float ca = a.lo[axis] + a.hi[axis], cb_ = b.lo[axis] + b.hi[axis];
      return ca < cb_ || (ca == cb_ && a.prim < b.prim);
    });
    left = Range{};
    right = Range{};
    left.begin = r.begin;
    left.end = right.begin = mid;
    right.end = r.end;
    const __m128 mask = xyz_mask();
    for (Range* side : {&left, &right}) {
      for (size_t i = side->begin; i < side->end; ++i) {
        const __m128 lo = load_lo(refs[i], mask), hi = load_hi(refs[i]), c = _mm_add_ps(lo, hi);
        side->box.extend(lo, hi);
        side->centroid.extend(c, c);
      }
    }
  }

 private:
  /// Recording: keeps the plane between bins b - 1 and b of each axis whose both sides hold
  /// references, with the cost the sweep computed.
  static void record_plane(Scratch& scratch, int b, __m128 valid, __m128 cost, __m128i left, __m128i right) {
    alignas(16) float c[4], ok[4];
    alignas(16) uint32_t l[4], rr[4];
    _mm_store_ps(c, cost);
    _mm_store_ps(ok, valid);
    _mm_store_si128(reinterpret_cast<__m128i*>(l), left);
    _mm_store_si128(reinterpret_cast<__m128i*>(rr), right);
    for (int a = 0; a < 3; ++a) {
      if (accel::bit_cast<uint32_t>(ok[a]) == 0) continue;
      scratch.planes[a].push_back({float(b), c[a], l[a], rr[a]});
    }
  }
  /// Recording: one Candidates step per axis, the bin index turned into the plane's position.
  void record_candidates(Scratch& scratch, uint32_t id, const BinMap& map, int depth) const {
    for (int a = 0; a < 3; ++a) {
      std::vector<SplitCandidate>& planes = scratch.planes[a];
      for (SplitCandidate& c : planes) c.pos = plane_position(map, a, int(c.pos));
      if (sink_.records(depth)) sink_.candidates(id, a, planes.data(), planes.size());
      planes.clear();
    }
  }

  const BvhBuildOptions& o_;
  Sink& sink_;
  int ppt_shift_ = -1;  ///< log2(prims_per_test) when it is a power of two
};

}  // namespace accel::binned
