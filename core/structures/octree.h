#pragma once
// Octree (lecture "Octree"): start with a cube around the scene, subdivide a cell into 8
// equal children until it holds few triangles or is deep enough. The traversal is the
// lecture's OctreeNode::Trace (after Bertolami's octree notes) written iteratively with an
// explicit stack, children visited front to back by the ray-octant order of Revelles, Urena
// & Lastra 2000, "An efficient parametric algorithm for octree traversal".
//
// Design decisions (the issue leaves them open):
//  * Root = a CUBE around the non-degenerate triangles (centred on their box): all children
//    of a node are equal cubes as in the lecture, and a flat scene (zero-thickness bounding
//    box) still gets a root with volume, so its boxes and split planes work unchanged.
//  * Node boxes are IMPLICIT (never stored): a node's box is its parent's box halved towards
//    its octant, computed by octree_child_box() in the build, the traversal and the viewer
//    alike, so children tile their parent bit for bit. Nodes are 8 bytes; the traversal
//    keeps the box of each level of its current path (depth <= 40). A viewer-only parent
//    array lets node_view() rebuild the box of any single node.
//  * Children of a node are 8 contiguous nodes in octant order; every block of 8 is
//    allocated after the root, so a node's octant is (id - 1) % 8.
//  * Empty leaves are kept (8 children always) but the traversal never pushes them: they
//    cannot hold a hit, so they cost neither a box test nor a stack entry, and no event.
//  * Defaults, measured single-threaded on bunny, dabrovic_sponza and the procedural
//    stadium, soup and cornell: order=sorted (1.4-3.5x faster than fixed), insert=exact
//    (40-60% of bbox's references, queries 10-35% faster, builds 2-5x slower),
//    max_prims=8 (2 and 4 were slower: more nodes and cache misses outweigh fewer triangle
//    tests; 12 and 16 about equal), max_depth=16: 10 is too shallow for the teapot in a
//    stadium (rays aimed at the 'teapot' ran 2.5x slower than at 14), 16 leaves margin for
//    a 65536:1 ratio between the scene and its details, and deeper costs nothing since
//    leaves stop earlier (see build_octree()).
//  * ct=2 for the no-gain stop (issue #31; bench, 2 threads, 512x512 primary rays, against
//    ct=0, the count of references alone, which the octree used before): on crytek_sponza,
//    sibenik, dragon, bunny, lost_empire and sports_car the same ray speed within the
//    bench's noise (+-10%), builds 10-25% faster, 25-50% less memory; on procedural:huge
//    (10M triangles) 10 references per triangle instead of 51, peak memory 3.1 instead of
//    10.4 GB, 1M random rays in 4.5 s instead of 90. ct=3 was 3-5% slower on the meshes.
//  * A 2D scene (the blackboard) has its own defaults, max_prims=1 and ct=0: the lecture's
//    quadtree, split until a cell holds one triangle (issue #50). The 3D defaults judge a
//    split by its cost, and on the blackboard's ten triangles no split pays: 3 ct + refs / 2
//    >= 10 for any split of the root (ct=2), which stays one no-gain leaf. Right for speed,
//    but the lecture is there to draw the subdivision. Parameters given explicitly win.
#include <cstdint>
#include <type_traits>
#include <vector>

#include "structure.h"

namespace accel {

/// Deepest level the octree can be built to (root = depth 0): the range of max_depth, and
/// what sizes the traversal's fixed stack.
inline constexpr int kOctreeMaxDepth = 40;

/// How a triangle is assigned to the children of a node being split.
enum class OctreeInsert : uint8_t {
  Bbox,   ///< to every child its bounding box overlaps (the lecture's "use bbox of objects")
  Exact,  ///< to every child the triangle itself overlaps (Akenine-Moller 2001 separating axes)
};

/// In which order the traversal visits the children of an inner node.
enum class OctreeOrder : uint8_t {
  Sorted,  ///< front to back: octants in the order the ray passes them (Revelles et al. 2000)
  Fixed,   ///< octant 0..7, the lecture's unsorted "for each child_node"
};

/// One node, 8 bytes. Its box is implicit (see octree_child_box()).
struct OctreeNode {
  static constexpr uint32_t kInner = 0xFFFFFFFFu;
  /// Inner node: id of its first child; children are first..first+7 in octant order.
  /// Leaf: offset of its triangles in OctreeData::prim_ids.
  uint32_t first = 0;
  /// Inner node: kInner. Leaf: number of triangles (0 = empty leaf).
  uint32_t count = 0;
  bool leaf() const { return count != kInner; }
};
static_assert(sizeof(OctreeNode) == 8, "octree nodes are two 32-bit words");

/// The box of child `octant` (bit 0 = upper half in x, bit 1 = in y, bit 2 = in z) of a node
/// whose box is `parent`. The split point is 0.5*min + 0.5*max (no overflow, inside the box);
/// siblings share it bit for bit, so children tile the parent with no gap.
inline Aabb octree_child_box(const Aabb& parent, unsigned octant) {
  const Vec3 mid = 0.5f * parent.min + 0.5f * parent.max;
  Aabb box;
  for (int axis = 0; axis < 3; ++axis) {
    const bool upper = (octant >> axis) & 1u;
    box.min[axis] = upper ? mid[axis] : parent.min[axis];
    box.max[axis] = upper ? parent.max[axis] : mid[axis];
  }
  return box;
}

/// The octree's root: a cube around `bounds` (the non-degenerate triangles' box) centred on
/// it, grown where rounding would leave part of `bounds` outside. Falls back to `bounds`
/// itself on an axis where the cube would overflow float. `planar` (a 2D scene): a square
/// in x and y, z as in `bounds` (flat).
Aabb octree_root_box(const Aabb& bounds, bool planar = false);

/// True when triangle (a, b, c) overlaps the closed box `box`. Separating axis test of
/// Akenine-Moller 2001, "Fast 3D Triangle-Box Overlap Testing" (box normals, triangle normal,
/// 9 edge cross products), evaluated in double on a box enlarged by a relative 2^-20 of its
/// half size (plus 2^-40 of the triangle's distance), so rounding can only add a triangle,
/// never lose one that touches the box.
bool triangle_overlaps_box(const Vec3& a, const Vec3& b, const Vec3& c, const Aabb& box);

/// Build settings (the structure's parameters plus the memory budget).
struct OctreeBuildOptions {
  int max_prims = 8;                               ///< a cell with <= max_prims triangles is a leaf
  int max_depth = 16;                              ///< deepest level (root = 0), <= kOctreeMaxDepth
  OctreeInsert insert = OctreeInsert::Exact;       ///< child assignment test
  /// Cost of one node visit in triangle tests, for the no-gain stop (build_octree()); 0 =
  /// the count of references alone.
  double ct = 2.0;
  /// The build fails beyond this many nodes or triangle references: what OctreeNode's 32-bit
  /// child ids and offsets hold. The memory budget (memory_limit) is what stops a build
  /// first on any real machine; tests set these lower to reach the failure quickly.
  size_t node_limit = OctreeNode::kInner - 8;
  size_t reference_limit = OctreeNode::kInner - 1;
  size_t memory_limit = SIZE_MAX;                  ///< ... or when its nodes and references pass these bytes
};

/// How many leaves stopped for which reason (stats and tests).
struct OctreeLeafReasons {
  size_t few_prims = 0;   ///< at most max_prims triangles
  size_t max_depth = 0;   ///< reached max_depth
  size_t no_gain = 0;     ///< splitting would not lower the expected triangle tests
  size_t inseparable = 0; ///< all of its parent's triangles, which splitting cannot separate
  size_t tiny_box = 0;    ///< box too small to halve in float
};


/// A built octree: plain data.
struct OctreeData {
  Aabb root_box;                  ///< box of node 0 (empty when there are no triangles)
  std::vector<OctreeNode> nodes;  ///< nodes[0] is the root; always at least one node
  std::vector<uint32_t> prim_ids; ///< triangle ids of all leaves, leaf by leaf
  std::vector<uint32_t> parents;  ///< parent id per node (root: kNoNode); viewer only
  std::vector<uint8_t> depths;    ///< depth per node; viewer and stats only
  OctreeLeafReasons reasons;
  /// Built over a 2D scene: a quadtree (see build_octree()).
  bool planar = false;
};

/// Children per inner node as the lecture draws them: 8, or the quadtree's 4 (a 2D scene,
/// whose upper-z octants, ids first + 4..7, stay empty leaves).
inline unsigned octree_child_count(const OctreeData& data) { return data.planar ? 4u : 8u; }
/// Whether node `id` is one of a quadtree's unused upper-z octants (never drawn or counted).
inline bool octree_unused_octant(const OctreeData& data, size_t id) { return data.planar && id > 0 && ((id - 1) & 4u); }
/// The nodes of the tree the lecture draws: all, or a quadtree's root and four per inner node.
inline size_t octree_node_count(const OctreeData& data) {
  return data.planar && !data.nodes.empty() ? 1 + (data.nodes.size() - 1) / 2 : data.nodes.size();
}

/// Builds an octree over `scene.valid_prims()`. Over a 2D scene (Scene::planar()) it is the
/// lecture's quadtree, by the same code: the root is a square, cells split in x and y only,
/// and triangles go to the four lower-z octants of each block of 8 alone (the upper four stay
/// empty leaves, which the traversal never visits and node_children() / for_each_node()
/// leave out); the no-gain stop counts refs / 2 (a child has half the node's perimeter).
/// A node becomes a leaf when it holds at most
/// max_prims triangles, is at max_depth, is too small to halve in float, or when splitting
/// cannot help:
///  * no gain: splitting would not lower the expected cost of a ray through the node. Each
///    child has a quarter of the node's surface area, so a ray through it meets 2 children
///    on average and tests refs / 4 of the children's references: a split pays when
///    3 ct + refs / 4 < n (the node and its two children visited, ct triangle tests each,
///    against the leaf's n tests). ct = 0 is the count alone (refs < 4n), which lets the
///    last levels split nodes of a dozen triangles into cells of five that hold each
///    triangle 3.5 times over: 51 references per triangle on procedural:huge.
///  * inseparable: a child keeping ALL of its parent's triangles becomes a leaf when the
///    split was poor (references at least doubled) or the triangles' bounds cover the whole
///    child. Triangles sharing a vertex or an edge, or overlapping in a plane, stay together
///    in every cell around the shared part, so refining there could only multiply nodes up
///    to max_depth; a compact cluster in a big cell (the teapot in the stadium) is neither
///    and is refined until its triangles separate.
/// Errors (naming max_depth and max_prims) when the node or reference limit of `options`
/// would be exceeded; never allocates beyond them.
///
/// Progress to `control`: the share of the scene in finished leaves, where the root holds
/// share 1 and an inner node splits its share among its 8 children in proportion to the
/// triangle references each receives (a duplicated triangle counts once per child, so the
/// shares stay a partition and the sum ends at exactly 1; counting triangles in leaves
/// instead would pass N with duplicates). Cancel is polled per node; a cancelled build
/// returns cancelled_error(). Progress is reported from the calling thread only.
///
/// Runs on TBB's threads (the caller's task_arena): the children of a node holding many
/// triangles are built as parallel tasks and spliced in octant order, so the tree (nodes,
/// their order, the leaves' triangle lists) is the same for any thread count.
/// With a `recorder`, every construction step is recorded (build_trace.h), serially; the tree
/// is the same and the steps' node ids are its ids. Steps: scene_box (the valid triangles'
/// box), node (root cube, its triangles), then depth-first per node: leaf (reason FewPrims,
/// MaxDepth, NoGain, NoProgress for inseparable, TooThin for a box too small to halve), or subdivide
/// (its 8 child ids in octant order) followed by each child's node and own steps, child 0's
/// subtree first; done (node count).
Result<OctreeData> build_octree(const Scene& scene, const OctreeBuildOptions& options,
                                BuildControl* control = nullptr, BuildRecorder* recorder = nullptr);

/// Everything the octree's parameters set: the build and the children's visiting order.
struct OctreeOptions {
  OctreeBuildOptions build;
  OctreeOrder order = OctreeOrder::Sorted;
  /// The defaults over a 2D scene (ParamSpec::planar_default): the lecture's quadtree,
  /// max_prims=1 and ct=0 (see the design decisions above); the rest as in 3D.
  static OctreeOptions planar_defaults() {
    OctreeOptions o;
    o.build.max_prims = 1;
    o.build.ct = 0.0;
    return o;
  }
};

/// Octree over the scene's non-degenerate triangles. Parameters: max_prims, max_depth,
/// insert (bbox|exact), ct, order (sorted|fixed); over a 2D scene max_prims and ct default
/// to OctreeOptions::planar_defaults().
class Octree final : public StructureWithTraversal<Octree> {
 public:
  /// The one declaration of the octree's parameters.
  static const ParamTable<OctreeOptions>& param_table();
  static std::vector<ParamSpec> param_specs() { return param_table().specs(); }
  std::string name() const override { return "octree"; }
  void for_each_node(const std::function<void(const NodeView&)>& fn) const override;
  NodeView node_view(NodeId id) const override;
  std::vector<uint32_t> node_prims(NodeId id) const override;
  std::vector<NodeId> node_children(NodeId id) const override;
  /// The built data, for tests.
  const OctreeData& data() const { return data_; }

  /// The one traversal: the lecture's OctreeNode::Trace, iterative. A node is skipped when
  /// the ray misses its box (MissedBounds) or enters it beyond the closest hit so far
  /// (BeyondClosestHit, checked when pushed and again when popped, since a triangle can
  /// straddle children and the closest hit may lie in a later child). Children are tested
  /// in visiting order and the hit ones pushed in reverse, so the first pops first.
  template <TraversalSink Sink>
  Hit traverse(const Ray& ray, Sink& sink) const;

 protected:
  Status build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) override;
  BuildStats compute_stats() const override { return stats_; }

 private:
  // DFS that pushes up to 8 children per level holds at most 7 per level + 1 entries.
  static constexpr int kStackSize = 8 * (kOctreeMaxDepth + 1);

  /// A node waiting on the traversal's stack: its id, its depth and the ray's interval in it.
  struct StackEntry {
    NodeId node;
    int depth;
    float t_enter, t_exit;
  };
  /// The box of a node on the traversal's current path.
  struct PathBox {
    Vec3 min, max;  // glm's defaulted constructor leaves these uninitialised: no per-ray fill
  };
  /// A node's children's slabs along the ray: per axis and half (0 lower, 1 upper), the
  /// distance to the near plane and to the (widened) far plane.
  struct ChildSlabs {
    float near_t[3][2], far_t[3][2];
  };

  /// The children's visiting order: octant i ^ mask is tested i-th.
  ACCEL_FORCE_INLINE unsigned visiting_mask(const Ray& ray) const;
  static ACCEL_FORCE_INLINE ChildSlabs child_slabs(const PathBox& box, const BoxTester& boxes);
  /// Tests the children of inner node `node` (entry `e`) in visiting order: the ones the ray
  /// enters before the closest hit go to `hit_children`, in that order; returns how many.
  /// The others are culled, and a recording sink gets the order (OctreeOrderVars).
  template <TraversalSink Sink>
  ACCEL_FORCE_INLINE int test_children(const Ray& ray, const StackEntry& e, const OctreeNode& node,
                                       const ChildSlabs& slabs, unsigned mask, float closest_t,
                                       StackEntry hit_children[8], Sink& sink) const;

  const Scene* scene_ = nullptr;
  OctreeData data_;
  OctreeOrder order_ = OctreeOrder::Sorted;
  BuildStats stats_;
};

template <TraversalSink Sink>
Hit Octree::traverse(const Ray& ray, Sink& sink) const {
  const TriangleTester tester(ray, kernel_);
  Hit closest = no_hit(ray);
  const std::vector<OctreeNode>& nodes = data_.nodes;
  // An empty root holds nothing to find.
  if (!scene_ || nodes.empty() || nodes[0].count == 0) return finish_query(closest, sink);
  const BoxTester boxes(ray);
  float t0 = 0.0f, t1 = 0.0f;
  if (!boxes.intersect(data_.root_box, ray.tmin, ray.tmax, &t0, &t1)) {
    sink.cull(0, 0, CullReason::MissedBounds, 0.0f);
    return finish_query(closest, sink);
  }
  // Box of the node currently visited at each depth of the path. A popped child's parent is
  // still path[depth - 1]: since the child was pushed, only nodes of the parent's subtree
  // (all deeper) were visited.
  PathBox path[kOctreeMaxDepth + 1];
  path[0] = {data_.root_box.min, data_.root_box.max};
  StackEntry stack[kStackSize];
  int top = 0;
  stack[top++] = {0, 0, t0, t1};
  sink.push(0, 0, t0);
  const unsigned mask = visiting_mask(ray);
  while (top > 0) {
    const StackEntry e = stack[--top];
    sink.pop(e.node, e.depth, e.t_enter);
    if (e.t_enter > closest.t) {
      sink.cull(e.node, e.depth, CullReason::BeyondClosestHit, e.t_enter);
      continue;
    }
    // The node's box, from its parent's. Written here, not in a helper returning a PathBox:
    // that one cost the fast path ~10% (1 thread, bunny; GCC allocated the loop's registers
    // differently) for the same instructions.
    if (e.depth > 0) {
      Aabb parent;
      parent.min = path[e.depth - 1].min;
      parent.max = path[e.depth - 1].max;
      const Aabb box = octree_child_box(parent, (e.node - 1u) & 7u);
      path[e.depth] = {box.min, box.max};
    }
    sink.visit(e.node, e.depth, e.t_enter, e.t_exit);
    const OctreeNode node = nodes[e.node];
    if (node.leaf()) {
      for (uint32_t k = node.first; k < node.first + node.count; ++k)
        test_triangle(*scene_, tester, data_.prim_ids[k], closest, sink);
      continue;
    }
    StackEntry hit_children[8];
    int hits = test_children(ray, e, node, child_slabs(path[e.depth], boxes), mask, closest.t, hit_children, sink);
    while (hits > 0) {
      const StackEntry& c = hit_children[--hits];
      ACCEL_DCHECK(top < kStackSize);
      stack[top++] = c;
      sink.push(c.node, c.depth, c.t_enter);
    }
  }
  return finish_query(closest, sink);
}

// Sorted: visiting octants i ^ mask for i = 0..7, where mask has a bit set for each axis the
// ray travels down, orders the children the ray passes as it passes them: along the ray each
// axis' half can only change from the near to the far one, so the octants it passes have
// increasing i (Revelles et al. 2000's first-node idea). A quadtree (2D scene) ignores z:
// its four quadrants are then the first four tested.
ACCEL_FORCE_INLINE unsigned Octree::visiting_mask(const Ray& ray) const {
  return order_ == OctreeOrder::Fixed ? 0u
                                      : unsigned(std::signbit(ray.dir.x)) | unsigned(std::signbit(ray.dir.y)) << 1 |
                                            unsigned(std::signbit(ray.dir.z) && !data_.planar) << 2;
}

// The children's ray intervals from the node's 9 planes (Revelles et al. 2000's parametric
// idea): per axis and half, the distance to the near plane and to the far plane, the latter
// widened (BoxTester::inv_dir_far) -- the very values BoxTester::intersect would compute for
// each child box, combined in its order, so every interval is bit-identical to it
// (conservative after Ize 2013, NaN-safe for zero direction components) without 8 separate
// box tests. (0.5f * x is exact, so the split point is the same float here and in
// octree_child_box() even if the compiler fuses multiply and add.)
ACCEL_FORCE_INLINE Octree::ChildSlabs Octree::child_slabs(const PathBox& box, const BoxTester& boxes) {
  ChildSlabs slabs;
  for (int axis = 0; axis < 3; ++axis) {
    const float mid = 0.5f * box.min[axis] + 0.5f * box.max[axis];
    const float inv = boxes.inv_dir[axis], inv_far = boxes.inv_dir_far[axis], org = boxes.org[axis];
    const bool negative = std::signbit(inv);
    const float lo = box.min[axis] - org, half = mid - org, hi = box.max[axis] - org;
    slabs.near_t[axis][0] = (negative ? half : lo) * inv;  // lower half [min, mid]
    slabs.far_t[axis][0] = (negative ? lo : half) * inv_far;
    slabs.near_t[axis][1] = (negative ? hi : half) * inv;  // upper half [mid, max]
    slabs.far_t[axis][1] = (negative ? half : hi) * inv_far;
  }
  return slabs;
}

template <TraversalSink Sink>
ACCEL_FORCE_INLINE int Octree::test_children(const Ray& ray, const StackEntry& e, const OctreeNode& node,
                                             const ChildSlabs& slabs, unsigned mask, float closest_t,
                                             StackEntry hit_children[8], Sink& sink) const {
  int hits = 0;
  // The child order, for a recording sink only: an empty struct otherwise, so the fast path
  // keeps no dead stores.
  struct NoOrder {};
  [[maybe_unused]] std::conditional_t<Sink::kRecords, OctreeOrderVars, NoOrder> order;
  for (unsigned i = 0; i < 8; ++i) {
    const unsigned octant = i ^ mask;
    const NodeId child = node.first + octant;
    if constexpr (Sink::kRecords) order.children[i] = {child, uint8_t(octant), OctreeOrderVars::Fate::Empty, 0, 0};
    if (data_.nodes[child].count == 0) continue;  // empty leaf
    float c0 = ray.tmin, c1 = ray.tmax;
    for (int axis = 0; axis < 3; ++axis) {
      const unsigned upper = (octant >> axis) & 1u;
      const float n = slabs.near_t[axis][upper], f = slabs.far_t[axis][upper];
      c0 = n > c0 ? n : c0;  // as in BoxTester: a NaN distance leaves the interval as is
      c1 = f < c1 ? f : c1;
    }
    if constexpr (Sink::kRecords) {
      order.children[i].t_enter = c0;
      order.children[i].t_exit = c1;
      order.children[i].fate = c0 > c1          ? OctreeOrderVars::Fate::Missed
                               : c0 > closest_t ? OctreeOrderVars::Fate::BeyondClosestHit
                                                : OctreeOrderVars::Fate::Pushed;
    }
    if (c0 > c1) {
      sink.cull(child, e.depth + 1, CullReason::MissedBounds, 0.0f);
    } else if (c0 > closest_t) {
      sink.cull(child, e.depth + 1, CullReason::BeyondClosestHit, c0);
    } else {
      hit_children[hits++] = {child, e.depth + 1, c0, c1};
    }
  }
  if constexpr (Sink::kRecords) {
    order.mask = mask;
    order.count = int(octree_child_count(data_));  // a quadtree's upper-z octants hold nothing
    sink.vars(order);
  }
  return hits;
}

}  // namespace accel
