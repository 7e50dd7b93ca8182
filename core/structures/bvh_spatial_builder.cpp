// Spatial-split BVH builder (Stich, Friedrich & Dietrich 2009, "Spatial Splits in Bounding
// Volume Hierarchies"), builder=sbvh.
//
// A splitter of the one top-down builder (bvh_top_down.h), whose nodes own their
// references. Per node:
//  1. the object split of the binned builder (BinnedSah::find_split/partition from
//     bvh_binned_detail.h: the same bins, sweep and costs), over the centroids of the
//     references' (clipped) boxes;
//  2. when its children overlap by more than sbvh_alpha times the root's area (Stich's
//     alpha test; also when there is no object split) and the node's share of the reference
//     budget allows it, the best spatial split: up to kSpatialBins equal bins over the
//     node's box on each axis, every reference chopped into the bins it overlaps (clipped by
//     split_triangle_box in large nodes, its box cut to the slabs in small ones:
//     kClipBinsThreshold), entry/exit counts per bin, and an SAH sweep over the boundaries;
//  3. the cheaper of the two, or a leaf by the leaf rule of every builder (leaf_verdict():
//     at most leaf_size references and no split cheaper than the leaf; forced at depth
//     kMaxBvhDepth - 1); the object median when there is no binned object split.
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
// Parallel as every top-down builder: large subtrees are TBB tasks building into their own
// chunks (nodes and leaf triangles in local pre-order), placed at their pre-order offsets
// at the end (top_down_tasks.h); the recorded build is the serial recursion from the root,
// with the same decisions, so the same tree.
#include "structures/bvh_spatial_builder.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "bit_cast.h"
#include "float_steps.h"
#include "check.h"
#include "parallel.h"
#include "structures/bvh_binned_detail.h"
#include "structures/bvh_top_down.h"

namespace accel {
namespace {

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

using binned::BinnedSah;
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
Range range_of(const std::vector<Ref>& refs) {
  Range r;
  const __m128 mask = binned::xyz_mask();
  for (const Ref& ref : refs) {
    const __m128 lo = binned::load_lo(ref, mask), hi = binned::load_hi(ref), c = _mm_add_ps(lo, hi);
    r.box.extend(lo, hi);
    r.centroid.extend(c, c);
  }
  r.begin = 0;
  r.end = refs.size();
  return r;
}

/// A node to build: its references (the node owns them), their bounds, its share of the
/// reference budget and of the progress.
struct SpatialWork {
  std::vector<Ref> refs;
  Range range;          ///< refs [0, refs.size()) with their bounds
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

/// A node's choice: the binned object split (with its partition, when the overlap test made
/// it), the spatial split, and which of the two is cheaper.
struct SpatialChoice {
  bool valid = false;  ///< any split
  float cost = 0.0f;   ///< the chosen split's
  bool use_spatial = false;
  BinSplit object;
  bool partitioned = false;  ///< the references are partitioned by `object` into left and right
  Range left, right;
  SpatialSplit spatial;
};

/// Per-task buffers: the object split's, and the spatial planes of one axis (recording).
struct SpatialScratch : binned::Scratch {
  std::vector<SplitCandidate> spatial_planes;
};

/// The SBVH splitter. A triangle may be in several leaves, so the leaves list their own
/// triangles; progress counts the leaves' shares of the build (SpatialWork::weight).
template <class Sink>
class SpatialSplitter {
 public:
  static constexpr bool kSahLeafRule = true;
  using Work = SpatialWork;
  using Split = SpatialChoice;
  using Scratch = SpatialScratch;

  SpatialSplitter(const Scene& scene, const BvhBuildOptions& o, Sink& sink)
      : scene_(scene), o_(o), sink_(sink), object_(o, sink) {}

  SpatialWork root() {
    const std::vector<uint32_t>& valid = scene_.valid_prims();
    const size_t n = valid.size();
    SpatialWork root;
    root.refs.resize(n);
    par::parallel_for(size_t(0), n,
                      [&](size_t i) { root.refs[i] = ref_of(valid[i], scene_.triangle_bounds(valid[i])); });
    root.range = range_of(root.refs);
    const double extra = std::max(0.0, double(o_.sbvh_budget) - 1.0) * double(n);
    root.budget = size_t(std::min(extra, double(uint32_t(-1)) - double(n)));  // uint32 prims indices
    root_area_ = root.range.box.area();
    return root;
  }
  uint64_t progress_total() const { return ProgressCounter::kWhole; }
  uint64_t progress_units(const SpatialWork& w) const { return uint64_t(w.weight * double(ProgressCounter::kWhole)); }
  size_t count(const SpatialWork& w) const { return w.refs.size(); }
  Aabb box(const SpatialWork& w) const { return w.range.box.aabb(); }
  void leaf(const SpatialWork& w, const SpatialChoice&, std::vector<uint32_t>& prims) const {
    for (const Ref& r : w.refs) prims.push_back(r.prim);
  }
  Aabb node_triangles(const SpatialWork& w, std::vector<uint32_t>& prims) const {
    prims.clear();
    leaf(w, SpatialChoice{}, prims);
    return w.range.centroid_bounds();
  }

  /// The object split, and where its children overlap (or there is none) and the budget and
  /// the depth allow, the spatial split; the cheaper of the two.
  SpatialChoice split(Scratch& scratch, SpatialWork& w, const Aabb&, int depth, uint32_t id) {
    std::vector<Ref>& refs = w.refs;
    const Range& r = w.range;
    SpatialChoice c;
    c.object = object_.find_split(scratch, refs.data(), r, depth, id);
    if (w.budget > 0 && depth < kMaxBvhDepth - 1) {
      bool overlap = true;  // no object split: try the spatial one
      if (c.object.valid) {
        c.partitioned = BinnedSah<Sink>::partition(refs.data(), r, c.object, c.left, c.right);
        if (c.partitioned) {
          Aabb both = c.left.box.aabb();
          overlap = clip_to(both, c.right.box.aabb()) && double(both.area()) > o_.sbvh_alpha * double(root_area_);
        }
      }
      if (overlap) c.spatial = find_spatial(scratch, refs, r, w.budget, depth, id);
    }
    c.use_spatial = c.spatial.valid && (!c.object.valid || c.spatial.cost < c.object.cost);
    c.valid = c.use_spatial || c.object.valid;
    c.cost = c.use_spatial ? c.spatial.cost : c.object.cost;
    return c;
  }

  /// The children of the split `c` (w.refs are consumed), with their shares of the budget
  /// left and of the progress, in proportion to their references.
  void partition(Scratch&, SpatialWork& w, SpatialChoice& c, SpatialWork& left, SpatialWork& right, int, uint32_t id,
                 float leaf_cost) {
    std::vector<Ref>& refs = w.refs;
    const size_t n = refs.size();
    size_t added = 0;  // references the split added
    if (c.use_spatial && spatial_split(refs, c.spatial, left, right, id, leaf_cost)) {
      added = left.refs.size() + right.refs.size() - n;
    } else {
      object_.split_objects(refs.data(), w.range, c.object, c.partitioned, c.left, c.right, id, leaf_cost);
      right.refs.assign(refs.begin() + long(c.right.begin), refs.begin() + long(c.right.end));
      refs.resize(c.left.end);
      left.refs = std::move(refs);
      left.range = c.left;
      right.range = c.right;
      left.range.begin = right.range.begin = 0;
      left.range.end = left.refs.size();
      right.range.end = right.refs.size();
    }
    w.refs = {};
    const size_t nl = left.refs.size(), nr = right.refs.size();
    ACCEL_CHECK(nl > 0 && nr > 0 && added <= w.budget);
    const size_t remaining = w.budget - added;
    left.budget = size_t(uint64_t(remaining) * nl / (nl + nr));
    right.budget = remaining - left.budget;
    left.weight = w.weight * double(nl) / double(nl + nr);
    right.weight = w.weight - left.weight;
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
  SpatialSplit find_spatial([[maybe_unused]] Scratch& scratch, const std::vector<Ref>& refs, const Range& r,
                            size_t budget, [[maybe_unused]] int depth, [[maybe_unused]] uint32_t id) const {
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
      if constexpr (Sink::kRecords) scratch.spatial_planes.clear();
      for (int k = 1; k < nb; ++k) {
        acc.extend(bin_box[k - 1]);
        count += enter[k - 1];
        const uint32_t nl = count, nr = right_count[k];
        if (nl == 0 || nr == 0 || nl >= n || nr >= n || size_t(nl) + nr - n > budget) continue;
        const float cost = o_.ct + (acc.area() * o_.leaf_cost(nl) + right_area[k] * o_.leaf_cost(nr)) * inv;
        if constexpr (Sink::kRecords) scratch.spatial_planes.push_back({pos[k], cost, nl, nr});
        if (!best.valid || cost < best.cost) best = {true, a, pos[k], cost};
      }
      if constexpr (Sink::kRecords) {
        const std::vector<SplitCandidate>& planes = scratch.spatial_planes;
        if (!planes.empty() && sink_.records(depth)) sink_.candidates(id, a, planes.data(), planes.size());
      }
    }
    return best;
  }

  /// Splits the references by the plane of `split` into the children (false, and nothing
  /// changed, if a side came out empty or as large as the node -- a rounding corner the
  /// sweep's counts cannot see). Straddling references are clipped to both sides, then,
  /// one by one, kept whole on one side when that is cheaper by the SAH (unsplitting).
  bool spatial_split(const std::vector<Ref>& refs, const SpatialSplit& split, SpatialWork& left, SpatialWork& right,
                     [[maybe_unused]] uint32_t id, [[maybe_unused]] float leaf_cost) const {
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
    left.range = range_of(left.refs);
    right.range = range_of(right.refs);
    if constexpr (Sink::kRecords)
      sink_.split(id, a, pos, split.cost, leaf_cost, uint32_t(nl), uint32_t(nr), uint32_t(straddling), true);
    return true;
  }

  const Scene& scene_;
  const BvhBuildOptions& o_;
  Sink& sink_;
  BinnedSah<Sink> object_;  ///< the object split, on the node's own references
  float root_area_ = 0.0f;  ///< set by root()
};

}  // namespace

BuildTree build_spatial_split_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                                   BuildRecorder* recorder) {
  return top_down::build_top_down<SpatialSplitter>(scene, options, progress, recorder);
}

}  // namespace accel
