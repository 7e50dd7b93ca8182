#pragma once
// The kd-tree's builder (kd_tree.h is the structure and its traversal): the node layout it
// writes, its options, and the middle, median and SAH splits with perfect splits, as
// bvh_builders.h is for the hierarchies. Design decisions of the build:
//  * split=sah is Wald & Havran 2006, "On building fast kd-Trees for Ray Tracing, and on
//    doing that in O(N log N)": one sorted event list per axis, swept once per node, kept
//    sorted through the split by filtering plus merging the (sorted) events of the
//    re-clipped straddlers, so no sort per node: O(N log N) overall. It tries all three
//    axes and ignores `axis`, as the lecture says ("try all 3 axes, choose the smallest
//    minimum"). Triangles lying in the split plane go to the side of lower cost. A plane on
//    the region's boundary is a candidate only to cut the triangles lying in it off into a
//    flat cell (their sec. 4.4; walls of axis-aligned rooms). It stops (leaf) when no plane
//    costs less than the leaf, ci * N.
//  * split=middle / median: the region's middle, or the median of the triangles' clipped box
//    centres, along the axis chosen by `axis`. They stop at leaf_size / max_depth, and two
//    guards stop the explosion of references a kd-tree risks (kd_builder.cpp, build_node()):
//    a split sending every triangle to both sides makes a leaf, and so does the third split
//    on a path whose SAH cost is not below the leaf's (pbrt's badRefines), e.g. around a
//    vertex shared by more than leaf_size triangles, which no plane ever separates.
//  * clip=on ("perfect splits", Havran 2000, Wald & Havran 2006 sec. 4.3): a triangle's
//    extent in a node is the box of the triangle clipped to the node's region, so split
//    candidates and the straddle test see only the part inside, and a triangle whose box
//    overlaps a child but which itself misses the child is not stored there. The clipping
//    is conservative (see kd_builder.cpp): it may keep a triangle that only grazes a child,
//    never drop one that touches it.
//  * Parallel (TBB), through the top-down driver (top_down_tasks.h): a node of at least
//    kTaskMinRefs triangles builds its two children as tasks; smaller ones build their
//    subtree serially into a chunk of their own, and the chunks are numbered in pre-order and
//    moved into place at the end. Every node is split exactly
//    as the serial recursion splits it (the same sorts on the same event orders), so the tree
//    is the same, bit for bit, for any thread count. The budgets fail exactly when the serial
//    build does (each node and reference is reserved on a shared counter; the event budget is
//    the serial build's live count, computed per path); progress is reported by the thread
//    that started the build only.
#include <cstdint>
#include <vector>

#include "build_control.h"
#include "build_trace.h"
#include "result.h"
#include "scene.h"
#include "structures/kd_node.h"

namespace accel {

/// The automatic depth limit for `n` triangles: round(8 + 1.3 log2 n), at most kKdMaxDepth
/// (pbrt's KdTreeAggregate, after Havran 2000).
int kd_auto_max_depth(size_t n);

/// Builds a kd-tree over `scene.valid_prims()`. Errors (naming the parameters to change)
/// when the node, reference or event budget of `options` would be exceeded, or
/// cancelled_error() when `control` is cancelled (polled per node).
///
/// Progress to `control`: the share of the scene in finished leaves, the root holding share
/// 1 and an inner node splitting its share between its children in proportion to the
/// triangles each receives (straddlers count on both sides, so the shares stay a partition
/// summing to 1). The automatic depth may retry with a lower limit; a retry continues from
/// the fraction reached, over what is left, so the reports never go back.
/// With a `recorder`, every construction step is recorded (build_trace.h), serially; the tree is the same.
/// Steps, depth first, below child first, node ids = the final (pre-order) node indices:
/// scene_box; per node: node (its region, as node_view reports it, and its triangles), then
/// split=sah: candidates per axis swept (every plane given a cost, in sweep order, the
/// empty-space bonus applied), middle/median: axis (the axis rule's choice); then split (C(B),
/// the leaf cost ci * N, the children's counts after clipping, the triangles in both) or leaf
/// (FewPrims, MaxDepth, or NoGain for sah's stop, no progress, bad refines and thin regions);
/// done. Of an automatic-depth build that retries, only the returned attempt's steps are kept.
Result<KdTreeData> build_kd_tree(const Scene& scene, const KdBuildOptions& options, BuildControl* control = nullptr,
                                 BuildRecorder* recorder = nullptr);

}  // namespace accel
