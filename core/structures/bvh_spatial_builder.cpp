// Spatial-split BVH builder (Stich, Friedrich & Dietrich 2009, "Spatial Splits in Bounding
// Volume Hierarchies"), builder=sbvh.
//
// Per node:
//  1. the object split of the binned builder (BinnedBuilder::find_split/partition from
//     bvh_binned_detail.h: the same bins, sweep and costs), over the centroids of the
//     references' (clipped) boxes;
//  2. when its children overlap by more than sbvh_alpha times the root's area (Stich's
//     alpha test; also when there is no object split) and the node's share of the reference
//     budget allows it, the best spatial split: up to kSpatialBins equal bins over the
//     node's box on each axis, every reference chopped into the bins it overlaps (clipped by
//     split_triangle_box in large nodes, its box cut to the slabs in small ones:
//     kClipBinsThreshold), entry/exit counts per bin, and an SAH sweep over the boundaries;
//  3. the cheaper of the two, or a leaf by the leaf rule of the other builders (at most
//     leaf_size references and no split cheaper than the leaf; forced at depth
//     kMaxBvhDepth - 1; the object median when there is no binned object split).
// A spatial split puts each straddling reference in both children, clipped to their sides,
// unless keeping it whole on one side is cheaper by the SAH ("reference unsplitting",
// Stich section 4.4, decided greedily reference by reference as in the paper).
//
// References: (triangle, box), 32 bytes as in the binned builder. A reference's box always
// contains the part of its triangle inside the reference's region (the node's slabs along
// its path): split_triangle_box clips the triangle in double and rounds outward, then
// intersects with the reference's box. The regions of a triangle's references cover it, so
// every point of it is in the box of some leaf that holds it, and of its ancestors.
//
// Budget: the root may add (sbvh_budget - 1) * n references. A node's share is handed down:
// what a spatial split does not use is divided between the children in proportion to their
// reference counts (Embree does the same), so every decision depends only on the node's
// references and its share -- not on the order the tasks run in. Every split strictly
// shrinks both children's reference counts, and the depth limit forces leaves as in the
// other builders.
//
// Parallel as the binned builder, through the top-down driver: large subtrees are TBB
// tasks building into their own chunks (nodes and leaf triangles in local pre-order), placed
// at their pre-order offsets at the end (top_down_tasks.h); the recorded build is the serial
// recursion from the root, with the same decisions, so the same tree.
#include "structures/bvh_spatial_builder.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "bit_cast.h"
#include "check.h"
#include "parallel.h"
#include "structures/bvh_binned_detail.h"
#include "structures/top_down_tasks.h"

namespace accel {
namespace {

/// The next float towards -inf / +inf of a finite f (std::nextafter without the library
/// call, which was a twentieth of the build).
inline float step_down(float f) {
  if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
  const uint32_t bits = accel::bit_cast<uint32_t>(f);
  return accel::bit_cast<float>(f > 0.0f ? bits - 1 : bits + 1);
}
inline float step_up(float f) { return -step_down(-f); }

/// The largest float <= d and the smallest float >= d (d finite, within float range).
inline float float_down(double d) {
  const float f = float(d);
  return double(f) > d ? step_down(f) : f;
}
inline float float_up(double d) {
  const float f = float(d);
  return double(f) < d ? step_up(f) : f;
}

/// Intersects `b` with `box` in place; false when the result is empty.
inline bool clip_to(Aabb& b, const Aabb& box) {
  b.min = glm::max(b.min, box.min);
  b.max = glm::min(b.max, box.max);
  return !b.empty();
}

}  // namespace

TriangleSplit split_triangle_box(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Aabb& box, int axis, float pos) {
  TriangleSplit s;
  const Vec3* v[3] = {&v0, &v1, &v2};
  bool any_left = false, any_right = false;
  // The vertices on each closed side (exact floats).
  for (const Vec3* p : v) {
    const float c = (*p)[axis];
    if (c <= pos) {
      s.left.extend(*p);
      any_left = true;
    }
    if (c >= pos) {
      s.right.extend(*p);
      any_right = true;
    }
  }
  // The edges that cross the plane strictly: their crossing is a vertex of both polygons.
  for (int k = 0; k < 3; ++k) {
    const Vec3& u = *v[k];
    const Vec3& w = *v[(k + 1) % 3];
    const float cu = u[axis], cw = w[axis];
    if (!((cu < pos && cw > pos) || (cu > pos && cw < pos))) continue;
    // t in (0, 1); each coordinate u + t (w - u) is computed in double with a relative error
    // of a few double epsilons of |u| + |w|, widened by that bound before rounding outward.
    const double t = (double(pos) - double(cu)) / (double(cw) - double(cu));
    Aabb crossing;
    crossing.min[axis] = crossing.max[axis] = pos;
    for (int b = 0; b < 3; ++b) {
      if (b == axis) continue;
      const double ub = u[b], wb = w[b];
      const double d = ub + t * (wb - ub);
      const double err = 8.0 * DBL_EPSILON * (std::abs(ub) + std::abs(wb));
      // The exact crossing lies between the edge's endpoints, which are floats.
      crossing.min[b] = std::max(float_down(d - err), std::min(u[b], w[b]));
      crossing.max[b] = std::min(float_up(d + err), std::max(u[b], w[b]));
    }
    s.left.extend(crossing);
    s.right.extend(crossing);
    any_left = any_right = true;
  }
  s.has_left = any_left && clip_to(s.left, box);
  s.has_right = any_right && clip_to(s.right, box);
  if (!s.has_left) s.left = Aabb{};
  if (!s.has_right) s.right = Aabb{};
  return s;
}

namespace {

using binned::BinnedBuilder;
using binned::BinSplit;
using binned::Box4;
using binned::Range;
using binned::Ref;

/// Nodes of at least this many references chop each reference into the spatial bins by
/// clipping its triangle (Stich et al.); smaller ones bin the reference's box cut to each
/// bin's slab, which bounds the clipped part too (an estimate for the sweep only: the chosen
/// split always clips). Clipping every node's bins made the build 5-7 times slower for
/// 0.01-0.8% lower SAH cost (bunny, crytek_sponza); with this threshold the cost is that of
/// clipping everywhere within 0.01%.
constexpr size_t kClipBinsThreshold = 4096;

inline Aabb box_of(const Ref& r) {
  Aabb b;
  b.min = Vec3(r.lo[0], r.lo[1], r.lo[2]);
  b.max = Vec3(r.hi[0], r.hi[1], r.hi[2]);
  return b;
}
inline Ref ref_of(uint32_t prim, const Aabb& b) {
  return {{b.min.x, b.min.y, b.min.z}, prim, {b.max.x, b.max.y, b.max.z}, 0.0f};
}
/// The node bounds of a set of references: box and doubled centroids, as the binned builder keeps them.
Range range_of(const std::vector<Ref>& refs, int depth) {
  Range r;
  const __m128 mask = binned::xyz_mask();
  for (const Ref& ref : refs) {
    const __m128 lo = binned::load_lo(ref, mask), hi = binned::load_hi(ref), c = _mm_add_ps(lo, hi);
    r.box.extend(lo, hi);
    r.centroid.extend(c, c);
  }
  r.begin = 0;
  r.end = refs.size();
  r.depth = depth;
  return r;
}

/// A node to build: its references (the node owns them), their bounds, its share of the
/// reference budget and of the progress.
struct Task {
  std::vector<Ref> refs;
  Range range;
  size_t budget = 0;    ///< references this subtree may add by spatial splits
  double weight = 1.0;  ///< share of the whole build (progress)
};

/// The best spatial split of a node: plane `pos` on `axis`, with the sweep's estimate.
struct SpatialSplit {
  bool valid = false;
  int axis = -1;
  float pos = 0.0f;
  float cost = 0.0f;
};

template <class Sink>
class SpatialBuilder {
 public:
  SpatialBuilder(const Scene& scene, const BvhBuildOptions& o, float root_area, Sink& sink)
      : scene_(scene), o_(o), sink_(sink), object_(o, nullptr, sink), root_area_(root_area) {}

  /// Serial build of `t` (consumed), appended to `out` in pre-order; returns its index
  /// there (the node's id in the recorded steps: the index in the finished tree).
  uint32_t build_serial(Task& t, top_down::Chunk<BuildNode>& out, ProgressCounter* progress,
                        uint32_t parent = kNoBuildNode) {
    const uint32_t index = uint32_t(out.nodes.size());
    out.nodes.emplace_back();
    out.nodes[index].box = t.range.box.aabb();
    Task left, right;
    if ((progress && progress->stopped()) || !decide(t, index, parent, left, right)) {
      out.nodes[index].first = uint32_t(out.prims.size());
      out.nodes[index].count = uint32_t(t.refs.size());
      for (const Ref& r : t.refs) out.prims.push_back(r.prim);
      if (progress) progress->add_share(t.weight);
      t.refs = {};
      return index;
    }
    const uint32_t l = build_serial(left, out, progress, index);
    const uint32_t r = build_serial(right, out, progress, index);
    out.nodes[index].left = l;
    out.nodes[index].right = r;
    return index;
  }

  /// One node: false when `t` becomes a leaf (t.refs are its triangles, in order);
  /// otherwise fills the children (t.refs are consumed). `id`, `parent`: for the sink.
  bool decide(Task& t, uint32_t id, uint32_t parent, Task& left, Task& right) {
    std::vector<Ref>& refs = t.refs;
    const size_t n = refs.size();
    Range r = t.range;
    r.begin = 0;
    r.end = n;
    object_.rebind(refs.data());
    if constexpr (Sink::kRecords) record_node(refs, r, id, parent);
    const bool at_depth_limit = r.depth >= kMaxBvhDepth - 1;
    BinSplit object;
    if (n > 1) object = object_.find_split(r, id);
    Range ol, orr;
    bool partitioned = false;
    SpatialSplit spatial;
    if (n > 1 && t.budget > 0 && !at_depth_limit) {
      bool overlap = true;  // no object split: try the spatial one
      if (object.valid) {
        partitioned = object_.partition(r, object, ol, orr);
        if (partitioned) {
          Aabb both = ol.box.aabb();
          overlap = clip_to(both, orr.box.aabb()) && double(both.area()) > o_.sbvh_alpha * double(root_area_);
        }
      }
      if (overlap) spatial = find_spatial(refs, r, t.budget, id);
    }
    const bool use_spatial = spatial.valid && (!object.valid || spatial.cost < object.cost);
    const bool any_split = use_spatial || object.valid;
    const float best_cost = use_spatial ? spatial.cost : object.cost;
    const float leaf_cost = o_.leaf_cost(n);
    const bool small = n <= size_t(o_.leaf_size);
    if (n <= 1 || (small && (!any_split || best_cost >= leaf_cost)) || at_depth_limit) {
      ACCEL_CHECK(small || at_depth_limit);
      if constexpr (Sink::kRecords) {
        const LeafReason why = at_depth_limit && !small ? LeafReason::MaxDepth
                               : any_split              ? LeafReason::NoGain
                                                        : LeafReason::FewPrims;
        const std::vector<uint32_t> prims = prims_of(refs);
        sink_.leaf(id, why, prims.data(), prims.size());
      }
      return false;
    }
    size_t added = 0;  // references the split added
    const bool done = use_spatial && spatial_split(refs, r, spatial, left, right, id, leaf_cost);
    if (done) {
      added = left.refs.size() + right.refs.size() - n;
    } else {
      const bool binned = object.valid && (partitioned || object_.partition(r, object, ol, orr));
      if (!binned) object_.median_split(r, ol, orr);
      if constexpr (Sink::kRecords) {
        if (binned) {
          sink_.split(id, object.axis, object_.split_position(object), object.cost, leaf_cost, uint32_t(ol.size()),
                      uint32_t(orr.size()), 0);
        } else {  // the object median: no cost computed
          const int axis = r.centroid.aabb().longest_axis();
          sink_.axis(id, axis, Vec3(0.0f));
          sink_.split(id, axis, 0.5f * (refs[ol.end - 1].lo[axis] + refs[ol.end - 1].hi[axis]), std::nanf(""),
                      leaf_cost, uint32_t(ol.size()), uint32_t(orr.size()), 0);
        }
      }
      right.refs.assign(refs.begin() + long(orr.begin), refs.begin() + long(orr.end));
      refs.resize(ol.end);
      left.refs = std::move(refs);
      left.range = ol;
      right.range = orr;
      left.range.begin = right.range.begin = 0;
      left.range.end = left.refs.size();
      right.range.end = right.refs.size();
    }
    t.refs = {};
    left.range.depth = right.range.depth = r.depth + 1;
    // The budget left, and the progress share, in proportion to the children's references.
    const size_t nl = left.refs.size(), nr = right.refs.size();
    ACCEL_CHECK(nl > 0 && nr > 0 && added <= t.budget);
    const size_t remaining = t.budget - added;
    left.budget = size_t(uint64_t(remaining) * nl / (nl + nr));
    right.budget = remaining - left.budget;
    left.weight = t.weight * double(nl) / double(nl + nr);
    right.weight = t.weight - left.weight;
    return true;
  }

 private:
  /// Spatial bins for a node of n references: kSpatialBins, fewer for small nodes (as the
  /// object split's bins), where a reference spans many bins and chopping it is the cost.
  static int spatial_bins(size_t n) { return int(std::min<size_t>(kSpatialBins, 4 + n / 2)); }

  /// How many of the planes pos[1..nb) are <= x (planes_at_or_below) or < x (planes_below),
  /// from a guess in [0, nb): pos is non-decreasing, so walking from the guess is exact.
  static int planes_at_or_below(const float* pos, int nb, int k, float x) {
    while (k + 1 < nb && pos[k + 1] <= x) ++k;
    while (k > 0 && pos[k] > x) --k;
    return k;
  }
  static int planes_below(const float* pos, int nb, int k, float x) {
    while (k + 1 < nb && pos[k + 1] < x) ++k;
    while (k > 0 && pos[k] >= x) --k;
    return k;
  }

  /// The plane positions of `nb` spatial bins on `axis`: pos[k] for k in [1, nb), non-decreasing.
  static void plane_positions(const Aabb& box, int axis, int nb, float* pos) {
    const float lo = box.min[axis], step = (box.max[axis] - lo) / float(nb);
    for (int k = 1; k < nb; ++k) pos[k] = lo + float(k) * step;
  }

  /// The best spatial split of the node (Stich et al. section 4.2): on each axis, the
  /// references chopped into equal bins over the node's box, the bins' boxes, entry and
  /// exit counts, and the SAH of every bin boundary. A plane is valid when both sides keep
  /// fewer references than the node (progress) and the duplicates fit the budget.
  SpatialSplit find_spatial(const std::vector<Ref>& refs, const Range& r, size_t budget, uint32_t id) {
    const size_t n = refs.size();
    const Aabb box = r.box.aabb();
    const float parent_area = box.area();
    const float inv = parent_area > 0.0f ? 1.0f / parent_area : 1.0f;
    SpatialSplit best;
    const int nb = spatial_bins(n);
    for (int a = 0; a < 3; ++a) {
      if (!(box.max[a] - box.min[a] > 0.0f)) continue;
      float pos[kSpatialBins];
      plane_positions(box, a, nb, pos);
      // The bin of x by arithmetic, a start for the exact count of planes (the planes are
      // rounded, so the guess may be one off).
      const float lo = box.min[a], scale = float(nb) / (box.max[a] - lo);
      const auto guess = [&](float x) {
        const float f = (x - lo) * scale;  // NaN (an infinite scale at x == lo) guesses 0
        return f >= 0.0f ? (f < float(nb - 1) ? int(f) : nb - 1) : 0;
      };
      Aabb bin_box[kSpatialBins];
      uint32_t enter[kSpatialBins] = {}, exit[kSpatialBins] = {};
      for (const Ref& ref : refs) {
        // Bin k lies between planes k and k + 1; a reference spans [first, last] (a flat one
        // on a plane belongs to the bin right of it).
        const int first = planes_at_or_below(pos, nb, guess(ref.lo[a]), ref.lo[a]);
        const int last = std::max(first, planes_below(pos, nb, guess(ref.hi[a]), ref.hi[a]));
        ++enter[first];
        ++exit[last];
        Aabb rest = box_of(ref);
        if (first == last) {
          bin_box[first].extend(rest);
          continue;
        }
        if (n < kClipBinsThreshold) {  // the reference's box cut to each bin's slab
          for (int j = first; j <= last; ++j) {
            Aabb piece = rest;
            if (j > first) piece.min[a] = pos[j];
            if (j < last) piece.max[a] = pos[j + 1];
            bin_box[j].extend(piece);
          }
          continue;
        }
        bool any = true;
        for (int j = first; j < last && any; ++j) {
          const TriangleSplit s = split_triangle_box(scene_.vertex(ref.prim, 0), scene_.vertex(ref.prim, 1),
                                                     scene_.vertex(ref.prim, 2), rest, a, pos[j + 1]);
          if (s.has_left) bin_box[j].extend(s.left);
          any = s.has_right;
          rest = s.right;
        }
        if (any) bin_box[last].extend(rest);
      }
      // Sweep: right sides from the top, then the planes from the bottom.
      float right_area[kSpatialBins];
      uint32_t right_count[kSpatialBins];
      Aabb acc;
      uint32_t count = 0;
      for (int k = nb - 1; k > 0; --k) {
        acc.extend(bin_box[k]);
        count += exit[k];
        right_area[k] = acc.area();
        right_count[k] = count;
      }
      acc = Aabb{};
      count = 0;
      if constexpr (Sink::kRecords) planes_.clear();
      for (int k = 1; k < nb; ++k) {
        acc.extend(bin_box[k - 1]);
        count += enter[k - 1];
        const uint32_t nl = count, nr = right_count[k];
        if (nl == 0 || nr == 0 || nl >= n || nr >= n || size_t(nl) + nr - n > budget) continue;
        const float cost = o_.ct + (acc.area() * o_.leaf_cost(nl) + right_area[k] * o_.leaf_cost(nr)) * inv;
        if constexpr (Sink::kRecords) planes_.push_back({pos[k], cost, nl, nr});
        if (!best.valid || cost < best.cost) best = {true, a, pos[k], cost};
      }
      if constexpr (Sink::kRecords)
        if (!planes_.empty() && sink_.records(r.depth)) sink_.candidates(id, a, planes_.data(), planes_.size());
    }
    return best;
  }

  /// Splits the references by the plane of `split` into the children (false, and nothing
  /// changed, if a side came out empty or as large as the node -- a rounding corner the
  /// sweep's counts cannot see). Straddling references are clipped to both sides, then,
  /// one by one, kept whole on one side when that is cheaper by the SAH (unsplitting).
  bool spatial_split(const std::vector<Ref>& refs, const Range& r, const SpatialSplit& split, Task& left, Task& right,
                     [[maybe_unused]] uint32_t id, [[maybe_unused]] float leaf_cost) {
    const int a = split.axis;
    const float pos = split.pos;
    const size_t n = refs.size();
    enum Side : uint8_t { kLeft, kRight, kBoth };
    std::vector<uint8_t> side(n);
    std::vector<std::pair<Aabb, Aabb>> pieces;  // of the references on both sides, in order
    std::vector<uint32_t> both;                 // their indices
    Aabb lbox, rbox;
    size_t nl = 0, nr = 0;
    std::vector<Ref> moved(refs);  // the references as they go to a single side (clipped when a part is empty)
    for (size_t i = 0; i < n; ++i) {
      const Ref& ref = refs[i];
      const Aabb b = box_of(ref);
      if (ref.lo[a] >= pos) {
        side[i] = kRight;
      } else if (ref.hi[a] <= pos) {
        side[i] = kLeft;
      } else {
        const TriangleSplit s = split_triangle_box(scene_.vertex(ref.prim, 0), scene_.vertex(ref.prim, 1),
                                                   scene_.vertex(ref.prim, 2), b, a, pos);
        if (s.has_left && s.has_right) {
          side[i] = kBoth;
          both.push_back(uint32_t(i));
          pieces.push_back({s.left, s.right});
          lbox.extend(s.left);
          rbox.extend(s.right);
          ++nl;
          ++nr;
          continue;
        }
        // Only one side holds a part of the triangle: the reference moves there, clipped
        // (neither: it cannot be lost, it goes left whole).
        side[i] = s.has_right ? kRight : kLeft;
        if (s.has_left) moved[i] = ref_of(ref.prim, s.left);
        if (s.has_right) moved[i] = ref_of(ref.prim, s.right);
      }
      (side[i] == kLeft ? lbox : rbox).extend(box_of(moved[i]));
      ++(side[i] == kLeft ? nl : nr);
    }
    // Reference unsplitting (Stich et al. section 4.4): the whole reference on one side
    // instead of its two parts, if that costs less (the other side keeps its box).
    for (size_t k = 0; k < both.size(); ++k) {
      const Aabb whole = box_of(refs[both[k]]);
      const float split_cost = lbox.area() * o_.leaf_cost(nl) + rbox.area() * o_.leaf_cost(nr);
      const float left_cost = nr > 1 ? merge(lbox, whole).area() * o_.leaf_cost(nl) + rbox.area() * o_.leaf_cost(nr - 1)
                                     : kInf;
      const float right_cost =
          nl > 1 ? lbox.area() * o_.leaf_cost(nl - 1) + merge(rbox, whole).area() * o_.leaf_cost(nr) : kInf;
      if (left_cost < split_cost && left_cost <= right_cost) {
        side[both[k]] = kLeft;
        lbox.extend(whole);
        --nr;
      } else if (right_cost < split_cost) {
        side[both[k]] = kRight;
        rbox.extend(whole);
        --nl;
      }
    }
    if (nl == 0 || nr == 0 || nl >= n || nr >= n) return false;
    left.refs.reserve(nl);
    right.refs.reserve(nr);
    size_t straddling = 0;
    for (size_t i = 0, k = 0; i < n; ++i) {
      const bool listed = k < both.size() && both[k] == i;
      if (listed && side[i] == kBoth) {
        left.refs.push_back(ref_of(refs[i].prim, pieces[k].first));
        right.refs.push_back(ref_of(refs[i].prim, pieces[k].second));
        ++straddling;
      } else {
        (side[i] == kLeft ? left.refs : right.refs).push_back(moved[i]);
      }
      if (listed) ++k;
    }
    left.range = range_of(left.refs, r.depth + 1);
    right.range = range_of(right.refs, r.depth + 1);
    if constexpr (Sink::kRecords)
      sink_.split(id, a, pos, split.cost, leaf_cost, uint32_t(nl), uint32_t(nr), uint32_t(straddling), true);
    return true;
  }

  /// The triangles of `refs` in order (recording only).
  static std::vector<uint32_t> prims_of(const std::vector<Ref>& refs) {
    std::vector<uint32_t> prims(refs.size());
    for (size_t i = 0; i < refs.size(); ++i) prims[i] = refs[i].prim;
    return prims;
  }
  /// The node's Node step: its box, the centroid bounds of its references' boxes, its triangles.
  void record_node(const std::vector<Ref>& refs, const Range& r, uint32_t id, uint32_t parent) {
    if (!sink_.records(r.depth)) {
      sink_.node(id, parent, r.depth, r.box.aabb(), Aabb{}, nullptr, refs.size());
      return;
    }
    Aabb centroids = r.centroid.aabb();
    centroids.min *= 0.5f;
    centroids.max *= 0.5f;
    const std::vector<uint32_t> prims = prims_of(refs);
    sink_.node(id, parent, r.depth, r.box.aabb(), centroids, prims.data(), prims.size());
  }

  const Scene& scene_;
  const BvhBuildOptions& o_;
  Sink& sink_;
  BinnedBuilder<Sink> object_;  ///< the object split, on the node's own references
  float root_area_;
  std::vector<SplitCandidate> planes_;  ///< recording only: one axis's spatial planes
};

/// The spatial-split builder under the top-down driver (top_down_tasks.h). A triangle may be
/// in several leaves, so each chunk lists its leaves' triangles; progress counts the
/// leaves' shares of the build (Task::weight).
template <class Sink>
class SpatialTasks : public top_down::SinkTasks<Sink> {
 public:
  using Node = BuildNode;
  using Task = accel::Task;
  using Stats = top_down::NoChunkStats;
  using ChunkT = top_down::Chunk<BuildNode>;

  SpatialTasks(const Scene& scene, const BvhBuildOptions& o, float root_area, ProgressCounter& progress, Sink& sink)
      : top_down::SinkTasks<Sink>(progress, sink), scene_(scene), o_(o), root_area_(root_area) {}

  size_t refs(const Task& t) const { return t.refs.size(); }
  void build_serial(Task& t, ChunkT& chunk) {
    SpatialBuilder<Sink>(scene_, o_, root_area_, this->sink_).build_serial(t, chunk, &this->progress_);
  }
  top_down::RootSplit split_root(Task& t, ChunkT& chunk, Task& left, Task& right) {
    SpatialBuilder<Sink> builder(scene_, o_, root_area_, this->sink_);
    chunk.node.box = t.range.box.aabb();
    if (!builder.decide(t, 0, kNoBuildNode, left, right)) {  // only at the depth limit
      chunk.node.count = uint32_t(t.refs.size());
      chunk.nodes.push_back(chunk.node);
      for (const Ref& r : t.refs) chunk.prims.push_back(r.prim);
      this->progress_.add_share(t.weight);
      return top_down::RootSplit::Leaf;
    }
    return top_down::RootSplit::Split;
  }

 private:
  const Scene& scene_;
  const BvhBuildOptions& o_;
  float root_area_;
};

}  // namespace

BuildTree build_spatial_split_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                                   BuildRecorder* recorder) {
  BuildTree tree;
  const std::vector<uint32_t>& valid = scene.valid_prims();
  const size_t n = valid.size();
  if (recorder) recorder->scene_box(scene.bounds());
  if (n == 0) return tree;
  Task root;
  root.refs.resize(n);
  par::parallel_for(size_t(0), n, [&](size_t i) { root.refs[i] = ref_of(valid[i], scene.triangle_bounds(valid[i])); });
  root.range = range_of(root.refs, 0);
  const double extra = std::max(0.0, double(options.sbvh_budget) - 1.0) * double(n);
  root.budget = size_t(std::min(extra, double(uint32_t(-1)) - double(n)));  // uint32 prims indices
  const float root_area = root.range.box.area();
  ProgressCounter shared(progress, ProgressCounter::kWhole);  // leaves add their share (weight) of the build
  const bool cancelled = with_build_sink(recorder, [&](auto& sink) {
    SpatialTasks<std::remove_reference_t<decltype(sink)>> tasks(scene, options, root_area, shared, sink);
    const auto chunks = top_down::TopDownTasks(tasks).build(root);
    if (shared.stopped()) return true;  // cancelled: the caller discards the tree
    top_down::stitch(*chunks, tree.nodes, &tree.prims);
    return false;
  });
  if (cancelled) return tree;
  tree.root = 0;
  return tree;
}

}  // namespace accel
