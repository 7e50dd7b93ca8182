// Binned SAH (lecture, BVH top-down with the cost function C(B), "search the minimum of C(B)"):
// instead of every split position, the centres are dropped into a fixed number of equal bins
// per axis and only the planes between bins are costed -- Wald 2007, "On fast construction
// of SAH-based BVHs". The default builder: the full sweep's quality at a fraction of its time.
//
// What makes it fast, compared with the splitters over PrimRef (median, sweep, PCA):
//  - one flat array of 32-byte references (box min/max, triangle index), built once in
//    parallel; the centroid is recomputed as min + max (twice the centre, which orders and
//    bins exactly like the centre) instead of being stored;
//  - one pass over a node's references bins all three axes at once (SSE2 for the box and
//    bin arithmetic), with a bin count that shrinks for small nodes;
//  - the partition is in place (two pointers) and returns the children's boxes and
//    centroid bounds, so no node ever rescans its references to find its bounds;
//  - binning over fixed slices for the largest nodes.
// The recursion, its leaf rule and its TBB tasks are the one top-down builder's
// (bvh_top_down.h); the split is bvh_binned_detail.h's, shared with the SBVH builder.
//
// Determinism: every decision depends only on the references of the node (bin bounds are
// min/max and bin counts are integer sums, both exact in any order, and partial bins are
// merged in slice order anyway), so the tree is the same for any thread count.
#include "structures/bvh_binned_builder.h"

#include <emmintrin.h>  // SSE2: part of every x86-64 CPU (as in geometry.h)

#include <vector>

#include "parallel.h"
#include "structures/bvh_binned_detail.h"
#include "structures/bvh_top_down.h"

namespace accel {
namespace {

using namespace binned;

/// The binned SAH splitter: a node is a range of one shared array of references with its
/// bounds (Range), split by the binned plane or, without one, at the object median.
template <class Sink>
class BinnedSplitter {
 public:
  static constexpr bool kSahLeafRule = true;
  using Work = Range;
  using Split = BinSplit;
  using Scratch = binned::Scratch;

  BinnedSplitter(const Scene& scene, const BvhBuildOptions& o, Sink& sink)
      : scene_(scene), object_(o, sink), refs_(scene.valid_prims().size()), leaf_whatever_split_(kept_whole(o)) {}

  /// The references and the root's bounds in one parallel pass; min/max reduce exactly in any order.
  Range root() {
    const std::vector<uint32_t>& valid = scene_.valid_prims();
    Range root = par::parallel_reduce(
        par::blocked_range<size_t>(0, refs_.size(), 4096), Range{},
        [&](const par::blocked_range<size_t>& br, Range acc) {
          for (size_t i = br.begin(); i != br.end(); ++i) {
            const uint32_t p = valid[i];
            const Aabb& b = scene_.triangle_bounds(p);
            refs_[i] = {{b.min.x, b.min.y, b.min.z}, p, {b.max.x, b.max.y, b.max.z}, 0.0f};
            const __m128 lo = _mm_set_ps(0.0f, b.min.z, b.min.y, b.min.x);
            const __m128 hi = _mm_set_ps(0.0f, b.max.z, b.max.y, b.max.x);
            const __m128 c = _mm_add_ps(lo, hi);
            acc.box.extend(lo, hi);
            acc.centroid.extend(c, c);
          }
          return acc;
        },
        [](Range a, const Range& b) {
          a.box.extend(b.box);
          a.centroid.extend(b.centroid);
          return a;
        });
    root.begin = 0;
    root.end = refs_.size();
    return root;
  }
  uint64_t progress_total() const { return refs_.size(); }
  uint64_t progress_units(const Range& r) const { return r.size(); }
  size_t count(const Range& r) const { return r.size(); }
  Aabb box(const Range& r) const { return r.box.aabb(); }
  BinSplit split(Scratch& scratch, Range& r, const Aabb&, int depth, uint32_t id) {
    // Binning a node that is a leaf whatever its best split (kept_whole()) was 7% of the
    // build. Recorded builds still bin it, for the lecture's Candidates and Leaf steps; the
    // tree is the same.
    if constexpr (!Sink::kRecords)
      if (r.size() <= leaf_whatever_split_) return BinSplit{};
    return object_.find_split(scratch, refs_.data(), r, depth, id);
  }
  void leaf(const Range& r, const BinSplit&, std::vector<uint32_t>& prims) const {
    for (size_t i = r.begin; i < r.end; ++i) prims.push_back(refs_[i].prim);
  }
  void partition(Scratch&, Range& r, BinSplit& split, Range& left, Range& right, int, uint32_t id, float leaf_cost) {
    object_.split_objects(refs_.data(), r, split, false, left, right, id, leaf_cost);
  }
  Aabb node_triangles(const Range& r, std::vector<uint32_t>& prims) const {
    prims.clear();
    leaf(r, BinSplit{}, prims);
    return r.centroid_bounds();
  }

 private:
  /// The largest node that is a leaf whatever its best split: one the leaf rule may keep
  /// whole (at most leaf_size) whose leaf costs no more than one traversal step, since a split
  /// costs ct plus a non-negative sum (exactly so in floats) and leaf_verdict() says NoGain.
  /// With the defaults (ct = ci = 1, prims_per_test 4) every leaf of up to 4. leaf_cost()
  /// grows with n, so the nodes it holds for are those up to a bound, found once here.
  static size_t kept_whole(const BvhBuildOptions& o) {
    size_t n = 0;
    while (n < size_t(o.leaf_size) && o.ct >= o.leaf_cost(n + 1)) ++n;
    return n;
  }

  const Scene& scene_;
  BinnedSah<Sink> object_;
  std::vector<Ref> refs_;
  const size_t leaf_whatever_split_;  ///< kept_whole(options)
};

}  // namespace

BuildTree build_binned_sah_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                                BuildRecorder* recorder) {
  return top_down::build_top_down<BinnedSplitter>(scene, options, progress, recorder);
}

}  // namespace accel
