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
//  * Parallel (TBB): a node of at least 2048 triangles builds its two children as tasks;
//    smaller ones build their subtree serially into a buffer of their own, and the buffers
//    are numbered in pre-order and moved into place at the end. Every node is split exactly
//    as the serial recursion splits it (the same sorts on the same event orders), so the tree
//    is the same, bit for bit, for any thread count. The budgets fail exactly when the serial
//    build does (each node and reference is reserved on a shared counter; the event budget is
//    the serial build's live count, computed per path); progress is reported by the thread
//    that started the build only.
#include <cstdint>
#include <vector>

#include "bit_cast.h"
#include "build_control.h"
#include "build_trace.h"
#include "result.h"
#include "scene.h"
#include "trace.h"
#include "vec_math.h"

namespace accel {

/// Deepest leaf a kd-tree can have (root = depth 0): the upper end of max_depth, and the
/// size of the traversal's stack (one pending far child per level at most).
inline constexpr int kKdMaxDepth = 64;

/// One kd-tree node, 8 bytes (pbrt-v4 KdTreeAggregate's KdTreeNode). The first (below)
/// child of an inner node is the next node in the array; only the second is stored.
struct KdNode {
  /// Inner node: the split position (float bits). Leaf: offset of its first triangle in
  /// KdTreeData::prim_ids.
  uint32_t payload = 0;
  /// Low 2 bits: split axis 0/1/2 of an inner node, or 3 for a leaf. Upper 30 bits: inner
  /// node = index of its above child (coordinates >= split); leaf = number of triangles.
  uint32_t bits = 3;

  bool leaf() const { return (bits & 3u) == 3u; }
  int axis() const { return int(bits & 3u); }
  float split() const { return accel::bit_cast<float>(payload); }
  NodeId above_child() const { return bits >> 2; }
  uint32_t prim_count() const { return bits >> 2; }
  uint32_t prim_offset() const { return payload; }

  static KdNode make_inner(int axis, float split, NodeId above) {
    return KdNode{accel::bit_cast<uint32_t>(split), (above << 2) | uint32_t(axis)};
  }
  static KdNode make_leaf(uint32_t offset, uint32_t count) { return KdNode{offset, (count << 2) | 3u}; }
};
static_assert(sizeof(KdNode) == 8, "kd-tree nodes are two 32-bit words");

/// Largest index / count the 30 upper bits of KdNode::bits hold.
inline constexpr uint32_t kKdMaxIndex = (1u << 30) - 1;

/// Where a node is split.
enum class KdSplit : uint8_t {
  Middle,  ///< middle of the node's region along the chosen axis
  Median,  ///< median of the triangles' (clipped) box centres along the chosen axis
  Sah,     ///< minimum of the surface area heuristic over all three axes (Wald & Havran 2006)
};

/// Which axis middle and median split (sah tries all three).
enum class KdAxis : uint8_t {
  RoundRobin,  ///< x, y, z, x, ... by depth (skipping an axis along which the region is flat)
  Longest,     ///< longest axis of the node's REGION (not of its triangles' box)
};

/// Build settings: the structure's parameters, validated, plus the memory budget.
///
/// Default SAH constants ct = 1, ci = 1, empty_bonus = 0.2, leaf_size = 1, clip on: measured
/// single-threaded (CPU time, 77k primary + random rays) on bunny, dragon, sibenik and
/// crytek_sponza, ci = 1 was fastest or within noise of it on every scene (ci = 1.5: 0-5%
/// slower and 40% more memory; ci = 3: 5-13% slower; pbrt's isect 80 / emptyBonus 0.5: 10-25%
/// slower, as the empty-space cuts it favours use up the depth limit and leave big leaves).
/// A node step costs about as much as a watertight triangle test here because it is
/// memory bound (the node load is the hottest instruction of the loop), so ci/ct ~ 1, near
/// Wald & Havran's K_I/K_T = 20/15. Their lambda = 0.8 (empty_bonus 0.2) sat between 0.1 and
/// 0.3, which were within noise; clip on was 5-20% faster than off; leaf_size 2 made no
/// difference, 1 leaves the decision to the SAH.
struct KdBuildOptions {
  KdSplit split = KdSplit::Sah;
  KdAxis axis = KdAxis::Longest;
  int max_depth = 0;            ///< deepest leaf; 0 = auto, round(8 + 1.3 log2 N)
  int leaf_size = 1;            ///< a node with <= leaf_size triangles is a leaf
  double ct = 1.0;              ///< SAH cost of one traversal step
  double ci = 1.0;              ///< SAH cost of one ray/triangle test
  double empty_bonus = 0.2;     ///< SAH cost factor (1 - empty_bonus) when one child is empty
  bool clip = true;             ///< perfect splits: clip triangles to the node's region
  size_t node_limit = size_t(1) << 26;       ///< build fails beyond this many nodes (512 MiB)
  size_t reference_limit = size_t(1) << 27;  ///< ... or this many triangle references (512 MiB)
  size_t event_limit = size_t(1) << 27;      ///< ... or this many live build events (1 GiB)
  /// The build's memory budget (memory_budget.h). build_kd_tree() lowers the three limits
  /// above to fit it: the nodes and the references a quarter of it each, the live build
  /// events (freed as leaves are made) the other half.
  size_t memory_limit = SIZE_MAX;
};

/// The automatic depth limit for `n` triangles: round(8 + 1.3 log2 n), at most kKdMaxDepth
/// (pbrt's KdTreeAggregate, after Havran 2000).
int kd_auto_max_depth(size_t n);

/// "middle", "median" or "sah": the parameter value of `split`.
const char* kd_split_name(KdSplit split);

/// How many leaves stopped for which reason (stats and tests).
struct KdLeafReasons {
  size_t few_prims = 0;    ///< at most leaf_size triangles
  size_t max_depth = 0;    ///< reached the depth limit
  size_t no_gain = 0;      ///< sah: no plane costs less than the leaf (Wald & Havran's termination)
  size_t no_progress = 0;  ///< the split sent every triangle to both sides
  size_t bad_refines = 0;  ///< middle/median: third split on the path that did not pay by SAH
  size_t thin = 0;         ///< middle/median: region too thin to put a plane inside
};

/// A built kd-tree: plain data.
struct KdTreeData {
  Aabb root_box;                   ///< region of node 0: box of the non-degenerate triangles
  std::vector<KdNode> nodes;       ///< nodes[0] is the root; always at least one node
  std::vector<uint32_t> prim_ids;  ///< triangle ids of all leaves, leaf by leaf
  int max_depth_limit = 0;         ///< the depth limit used (max_depth resolved)
  int depth = 0;                   ///< deepest leaf
  KdLeafReasons leaf_reasons;
};

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

/// Region of the below (`above` false: coordinates <= split) or above child of a node
/// whose region is `box`, split at `split` along `axis`.
inline Aabb kd_child_box(const Aabb& box, int axis, float split, bool above) {
  Aabb child = box;
  (above ? child.min : child.max)[axis] = split;
  return child;
}

}  // namespace accel
