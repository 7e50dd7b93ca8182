// Binned SAH (lecture, BVH top-down with the cost function C(B), "search the minimum of C(B)"):
// instead of every split position, the centres are dropped into a fixed number of equal bins
// per axis and only the planes between bins are costed -- Wald 2007, "On fast construction
// of SAH-based BVHs". The default builder: the full sweep's quality at a fraction of its time.
//
// What makes it fast, compared with the generic top-down recursion of bvh_top_down.h:
//  - one flat array of 32-byte references (box min/max, triangle index), built once in
//    parallel; the centroid is recomputed as min + max (twice the centre, which orders and
//    bins exactly like the centre) instead of being stored;
//  - one pass over a node's references bins all three axes at once (SSE2 for the box and
//    bin arithmetic), with a bin count that shrinks for small nodes;
//  - the partition is in place (two pointers) and returns the children's boxes and
//    centroid bounds, so no node ever rescans its references to find its bounds;
//  - no heap allocation per node: a serial subtree appends to one vector;
//  - TBB tasks for large subtrees through the top-down driver (top_down_tasks.h), and
//    binning over fixed slices for the largest nodes.
//
// Determinism: every decision depends only on the references of the node (bin bounds are
// min/max and bin counts are integer sums, both exact in any order, and partial bins are
// merged in slice order anyway), and nodes are renumbered in pre-order from the subtree
// sizes at the end, so the tree is the same for any thread count.
#include "structures/bvh_binned_builder.h"

#include <emmintrin.h>  // SSE2: part of every x86-64 CPU (as in geometry.h)

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>

#include "check.h"
#include "parallel.h"
#include "structures/bvh_binned_detail.h"
#include "structures/top_down_tasks.h"

namespace accel {
namespace {

using namespace binned;

/// The binned builder under the top-down driver (top_down_tasks.h). Its leaves index the
/// one shared reference order, so chunks have no triangles of their own; progress counts the
/// references placed.
template <class Sink>
class BinnedTasks : public top_down::SinkTasks<Sink> {
 public:
  using Node = BuildNode;
  using Task = Range;
  using Stats = top_down::NoChunkStats;
  using ChunkT = top_down::Chunk<BuildNode>;

  BinnedTasks(const BvhBuildOptions& o, Ref* refs, ProgressCounter& progress, Sink& sink)
      : top_down::SinkTasks<Sink>(progress, sink), o_(o), refs_(refs) {}

  size_t refs(const Range& r) const { return r.size(); }
  void build_serial(Range& r, ChunkT& chunk) {
    BinnedBuilder<Sink> builder(o_, refs_, this->sink_);
    chunk.nodes.reserve(Sink::kRecords ? 2 * r.size() / size_t(std::max(1, o_.leaf_size)) + 1 : r.size());
    builder.build_serial(r, chunk.nodes);
    this->progress_.add(r.size());
  }
  top_down::RootSplit split_root(Range& r, ChunkT& chunk, Range& left, Range& right) {
    BinnedBuilder<Sink> builder(o_, refs_, this->sink_);
    chunk.node.box = r.box.aabb();
    if (!builder.split_node(r, left, right)) {  // only at the depth limit
      chunk.node.first = uint32_t(r.begin);
      chunk.node.count = uint32_t(r.size());
      chunk.nodes.push_back(chunk.node);
      this->progress_.add(r.size());
      return top_down::RootSplit::Leaf;
    }
    return top_down::RootSplit::Split;
  }

 private:
  const BvhBuildOptions& o_;
  Ref* refs_;
};

}  // namespace

BuildTree build_binned_sah_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                                BuildRecorder* recorder) {
  BuildTree tree;
  const std::vector<uint32_t>& valid = scene.valid_prims();
  const size_t n = valid.size();
  if (recorder) recorder->scene_box(scene.bounds());
  if (n == 0) return tree;
  std::vector<Ref> refs(n);
  // References and root bounds in one parallel pass; min/max reduce exactly in any order.
  Range root = par::parallel_reduce(
      par::blocked_range<size_t>(0, n, 4096), Range{},
      [&](const par::blocked_range<size_t>& br, Range acc) {
        for (size_t i = br.begin(); i != br.end(); ++i) {
          const uint32_t p = valid[i];
          const Aabb& b = scene.triangle_bounds(p);
          Ref& ref = refs[i];
          ref = {{b.min.x, b.min.y, b.min.z}, p, {b.max.x, b.max.y, b.max.z}, 0.0f};
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
  root.end = n;
  root.depth = 0;
  ProgressCounter placed(progress, n);  // references placed in leaves
  const bool cancelled = with_build_sink(recorder, [&](auto& sink) {
    BinnedTasks<std::remove_reference_t<decltype(sink)>> tasks(options, refs.data(), placed, sink);
    const auto chunks = top_down::TopDownTasks(tasks).build(root);
    if (placed.stopped()) return true;  // cancelled: the caller discards the tree
    top_down::stitch(*chunks, tree.nodes);
    return false;
  });
  if (cancelled) return tree;
  tree.root = 0;
  tree.prims.resize(n);
  par::parallel_for(par::blocked_range<size_t>(0, n, 16384), [&](const par::blocked_range<size_t>& br) {
    for (size_t i = br.begin(); i != br.end(); ++i) tree.prims[i] = refs[i].prim;
  });
  return tree;
}

}  // namespace accel
