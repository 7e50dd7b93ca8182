#pragma once
// The kd-tree's data: its 8-byte node (pbrt-v4's layout), its options and the built tree,
// shared by the structure (kd_tree.h: traversal and viewer views) and its builder
// (kd_builder.h), so the structure's header does not include the builder's.
#include <cstdint>
#include <cstring>
#include <vector>

#include "bit_cast.h"
#include "geometry.h"
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

/// Region of the below (`above` false: coordinates <= split) or above child of a node
/// whose region is `box`, split at `split` along `axis`.
inline Aabb kd_child_box(const Aabb& box, int axis, float split, bool above) {
  Aabb child = box;
  (above ? child.min : child.max)[axis] = split;
  return child;
}

/// "middle", "median" or "sah": the parameter value of `split`.
const char* kd_split_name(KdSplit split);

}  // namespace accel
