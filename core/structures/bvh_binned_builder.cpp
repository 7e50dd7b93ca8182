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
//  - TBB tasks for subtrees of at least kTaskThreshold references, and binning over fixed
//    slices for the largest nodes.
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
#include "structures/bvh_chunks.h"

namespace accel {
namespace {

constexpr size_t kTaskThreshold = 4096;        // smaller subtrees are one serial task

using namespace binned;

/// The chunk of range `r` (bvh_chunks.h): a serial subtree below kTaskThreshold references,
/// else its root with the two children as tasks.
std::unique_ptr<BuildChunk> build_upper(const BvhBuildOptions& o, Ref* refs, const Range& r,
                                        ProgressCounter& progress) {
  auto u = std::make_unique<BuildChunk>();
  if (progress.stopped()) return u;  // cancelled: an empty subtree, discarded by the caller
  NullBuildSink no_steps;
  BinnedBuilder<NullBuildSink> builder(o, refs, no_steps);
  if (r.size() < kTaskThreshold) {
    u->nodes.reserve(r.size());
    builder.build_serial(r, u->nodes);
    u->size = u->nodes.size();
    progress.add(r.size());
    return u;
  }
  u->node.box = r.box.aabb();
  Range left, right;
  if (!builder.split_node(r, left, right)) {  // only at the depth limit
    u->node.first = uint32_t(r.begin);
    u->node.count = uint32_t(r.size());
    u->nodes.push_back(u->node);
    u->size = 1;
    progress.add(r.size());
    return u;
  }
  par::parallel_invoke([&] { u->left = build_upper(o, refs, left, progress); },
                       [&] { u->right = build_upper(o, refs, right, progress); });
  u->size = 1 + u->left->size + u->right->size;
  return u;
}

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
  if (recorder) {  // recorded: the serial build from the root (the same tree, in pre-order)
    BinnedBuilder<BuildRecorder> builder(options, refs.data(), *recorder);
    tree.nodes.reserve(2 * n / size_t(std::max(1, options.leaf_size)) + 1);
    builder.build_serial(root, tree.nodes);
    if (progress) progress->advance(1.0);
    tree.prims.resize(n);
    for (size_t i = 0; i < n; ++i) tree.prims[i] = refs[i].prim;
    return tree;
  }

  ProgressCounter shared_progress(progress, n);  // triangles placed in leaves
  const std::unique_ptr<BuildChunk> upper = build_upper(options, refs.data(), root, shared_progress);
  if (shared_progress.stopped()) return tree;  // cancelled: the caller discards the tree
  stitch_chunks(*upper, tree.nodes);
  tree.root = 0;
  tree.prims.resize(n);
  par::parallel_for(par::blocked_range<size_t>(0, n, 16384), [&](const par::blocked_range<size_t>& br) {
    for (size_t i = br.begin(); i != br.end(); ++i) tree.prims[i] = refs[i].prim;
  });
  return tree;
}

}  // namespace accel
