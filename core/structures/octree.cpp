#include "structures/octree.h"

#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <string>
#include <utility>

#include "parallel.h"
#include "structures/top_down_tasks.h"

namespace accel {

// [SECTION] Geometry: root cube, triangle/box overlap

Aabb octree_root_box(const Aabb& bounds, bool planar) {
  if (bounds.empty()) return bounds;
  // In double: max - min of floats near the float range would overflow in float. A 2D
  // scene's root is a square in x and y and keeps its flat z (a quadtree's root).
  const int axes = planar ? 2 : 3;
  double side = 0.0;
  for (int axis = 0; axis < axes; ++axis) side = std::max(side, double(bounds.max[axis]) - double(bounds.min[axis]));
  Aabb box = bounds;
  for (int axis = 0; axis < axes; ++axis) {
    const double centre = 0.5 * (double(bounds.min[axis]) + double(bounds.max[axis]));
    float lo = float(centre - 0.5 * side), hi = float(centre + 0.5 * side);
    if (!std::isfinite(lo)) lo = bounds.min[axis];
    if (!std::isfinite(hi)) hi = bounds.max[axis];
    // float() rounds to nearest: grow back over the scene where it rounded inwards.
    box.min[axis] = std::min(lo, bounds.min[axis]);
    box.max[axis] = std::max(hi, bounds.max[axis]);
  }
  return box;
}

// triangle_overlaps_box() is most of an octree build (58% of procedural:huge's): GCC builds
// it for AVX2 too and picks the clone at load time where the CPU has AVX2 (x86-64 ELF; clang
// 14, the sanitizer build, makes the plain one only). The same double operations in the same
// order, without contraction (-ffp-contract=off), so the same answers.
#if defined(__x86_64__) && defined(__ELF__) && !defined(__EMSCRIPTEN__)
#define ACCEL_OVERLAP_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define ACCEL_OVERLAP_CLONES
#endif

namespace {

/// The start every overlap test below shares: the triangle relative to the box centre and
/// the box's enlarged half size (see triangle_overlaps_box()). One function, so the partial
/// test of OctreeBuilder::child_mask() computes the very same doubles as the full one.
struct CentredTriangle {
  DVec3 v0, v1, v2;  // vertices minus the box centre
  DVec3 h;           // enlarged half size
};

ACCEL_FORCE_INLINE CentredTriangle centre_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Aabb& box) {
  const DVec3 centre = 0.5 * (DVec3(box.min) + DVec3(box.max));
  CentredTriangle t;
  t.v0 = DVec3(a) - centre;
  t.v1 = DVec3(b) - centre;
  t.v2 = DVec3(c) - centre;
  const DVec3 reach = glm::max(glm::abs(t.v0), glm::max(glm::abs(t.v1), glm::abs(t.v2)));
  const double far = std::max(reach.x, std::max(reach.y, reach.z));
  // Enlarged half size: double rounding of the products below is ~2^-52 of |v| and |h|, far
  // below these margins, so a triangle touching the closed box is always kept.
  t.h = 0.5 * (DVec3(box.max) - DVec3(box.min)) * (1.0 + 0x1p-20) + DVec3(far * 0x1p-40);
  return t;
}

/// The triangle's plane against the box: the box's projected radius onto the normal. Only
/// v0 is projected, so unlike the other 12 axes this one can reject a thin sliver whose
/// other vertex lies in the box (the normal's rounding tilts the plane): child_mask() runs
/// it where a vertex other than the first proves the rest.
ACCEL_FORCE_INLINE bool plane_overlaps(const CentredTriangle& t) {
  const DVec3 n = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
  const double d = glm::dot(n, t.v0);
  const double r = t.h.x * std::abs(n.x) + t.h.y * std::abs(n.y) + t.h.z * std::abs(n.z);
  return std::abs(d) <= r;
}

}  // namespace

ACCEL_OVERLAP_CLONES bool triangle_overlaps_box(const Vec3& a, const Vec3& b, const Vec3& c, const Aabb& box) {
  // Akenine-Moller 2001: the triangle and the box are disjoint iff one of 13 axes separates
  // them: the 3 box normals, the triangle normal and the 9 cross products of box normals
  // and triangle edges. Everything relative to the box centre, in double.
  const CentredTriangle t = centre_triangle(a, b, c, box);
  const DVec3 &v0 = t.v0, &v1 = t.v1, &v2 = t.v2, &h = t.h;

  // 1. Box normals: the triangle's bounding box against the box.
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = std::min(v0[axis], std::min(v1[axis], v2[axis]));
    const double hi = std::max(v0[axis], std::max(v1[axis], v2[axis]));
    if (lo > h[axis] || hi < -h[axis]) return false;
  }
  // 2. The 9 axes e_axis x edge f: (0, -f.z, f.y), (f.z, 0, -f.x), (-f.y, f.x, 0). The
  // projections of the three vertices take two distinct values, the box's radius is
  // h.y*|f.z| + h.z*|f.y| (for e_x). Written out per axis (the compiler kept the generic
  // index loop), the same products in the same order.
  const auto apart = [](double p0, double p1, double p2, double r) {
    return std::min(p0, std::min(p1, p2)) > r || std::max(p0, std::max(p1, p2)) < -r;
  };
  for (const DVec3& f : {v1 - v0, v2 - v1, v0 - v2}) {
    if (apart(-f.z * v0.y + f.y * v0.z, -f.z * v1.y + f.y * v1.z, -f.z * v2.y + f.y * v2.z,
              h.y * std::abs(f.z) + h.z * std::abs(f.y)))
      return false;
    if (apart(-f.x * v0.z + f.z * v0.x, -f.x * v1.z + f.z * v1.x, -f.x * v2.z + f.z * v2.x,
              h.z * std::abs(f.x) + h.x * std::abs(f.z)))
      return false;
    if (apart(-f.y * v0.x + f.x * v0.y, -f.y * v1.x + f.x * v1.y, -f.y * v2.x + f.x * v2.y,
              h.x * std::abs(f.y) + h.y * std::abs(f.x)))
      return false;
  }
  // 3. The triangle's plane against the box.
  return plane_overlaps(t);
}

// [SECTION] Builder

namespace {

/// Octants (bits of a mask) of the children of a node split at `mid` that the closed box
/// [lo, hi] reaches: per axis the lower half when lo <= mid, the upper when hi >= mid.
/// Closed intervals: a box touching the split plane reaches both sides.
ACCEL_FORCE_INLINE unsigned octants_reached(const Vec3& lo, const Vec3& hi, const Vec3& mid) {
  // Octants with bit `axis` clear (lower half) and set (upper half), per axis.
  static constexpr unsigned kLower[3] = {0x55u, 0x33u, 0x0Fu}, kUpper[3] = {0xAAu, 0xCCu, 0xF0u};
  unsigned mask = 0xFFu;
  for (int axis = 0; axis < 3; ++axis)
    mask &= (lo[axis] <= mid[axis] ? kLower[axis] : 0u) | (hi[axis] >= mid[axis] ? kUpper[axis] : 0u);
  return mask;
}

/// The part of the tree one task builds: the nodes below its root (the root itself lives
/// in the part of the task that split its parent), their leaves' triangles, viewer data.
/// Node and triangle offsets are local; splice() moves them to where the serial build
/// would have put them.
struct OctreePart {
  /// Parent entry of the children of the part's root, replaced by the root's id on splice.
  static constexpr uint32_t kPartRoot = 0xFFFFFFFEu;
  std::vector<OctreeNode> nodes;
  std::vector<uint32_t> prim_ids;
  std::vector<uint32_t> parents;
  std::vector<uint8_t> depths;
  OctreeLeafReasons reasons;
};

/// What child_mask() reads of a triangle, in one cache line: the scene keeps bounds,
/// indices and positions in three arrays, three misses per triangle and level.
struct alignas(64) OctreePrim {
  Aabb bounds;
  Vec3 v[3];
};

/// Reusable lists of the children's triangles, one per depth: a node's lists live while its
/// children (one level deeper) are built. One per task, never shared between threads.
struct OctreeScratch {
  std::vector<uint32_t> refs[kOctreeMaxDepth + 1];
  std::vector<uint8_t> masks[kOctreeMaxDepth + 1];
};

/// Top-down octree builder (lecture: "start with the bbox of the whole scene, subdivide a
/// cell into 8 equal sub-cells; stopping criterion: the number of objects, and maximal
/// depth"), plus the stops of build_octree()'s contract that keep extreme settings bounded.
///
/// Parallel (TBB): the children of a node with many triangles are built as 8 tasks, each
/// into its own OctreePart, spliced in octant order afterwards. The serial build allocates
/// a node's block of 8 children, then each child's subtree in turn, appending leaves'
/// triangles as it goes, so child k's subtree is one contiguous run of nodes and of
/// triangle ids after child k-1's: splicing the parts in order, with their offsets moved,
/// reproduces the serial numbering exactly, whatever the thread count.
///
/// Every construction step goes to `Sink` (build_trace.h): NullBuildSink for the normal
/// build, BuildRecorder for a recorded one, which always runs serially, so its node ids are
/// the finished tree's ids and its steps come depth-first, child 0's subtree first:
/// node(root), then per node either leaf(id, reason) or subdivide(id, its 8 children)
/// followed by each child's node(...) and its own steps in octant order. Leaf reasons:
/// FewPrims (<= max_prims), MaxDepth, and NoGain for the other stops (no gain, inseparable,
/// box too small to halve: splitting would not separate the triangles).
template <class Sink>
class OctreeBuilder {
 public:
  OctreeBuilder(const Scene& scene, const OctreeBuildOptions& options, BuildControl* control, bool parallel,
                Sink& sink)
      : scene_(scene), options_(options), control_(control), parallel_(parallel && !Sink::kRecords),
        sink_(sink), progress_(control, 0.0, 1.0),
        leaves_done_(&progress_, ProgressCounter::kWhole) {}

  /// The failure a build stopped with (checked in this order of priority by build_octree()).
  enum class Failure : int { None, Cancelled, Nodes, References, Memory };

  Result<OctreeData> run() {
    OctreeData data;
    Aabb bounds;
    for (uint32_t prim : scene_.valid_prims()) bounds.extend(scene_.triangle_bounds(prim));
    prims_.resize(scene_.triangle_count());
    par::parallel_for(par::blocked_range<size_t>(0, scene_.valid_prims().size(), 4096),
                      [&](const par::blocked_range<size_t>& r) {
                        for (size_t k = r.begin(); k < r.end(); ++k) {
                          const uint32_t prim = scene_.valid_prims()[k];
                          prims_[prim] = {scene_.triangle_bounds(prim),
                                          {scene_.vertex(prim, 0), scene_.vertex(prim, 1), scene_.vertex(prim, 2)}};
                        }
                      });
    data.root_box = octree_root_box(bounds, planar_);
    data.planar = planar_;
    sink_.scene_box(bounds);
    OctreePart main;  // the whole tree: its root is node 0, not outside
    add_node(main, kNoNode, 0);
    nodes_total_ = 1;
    OctreeScratch scratch;
    const std::vector<uint32_t>& all = scene_.valid_prims();
    OctreeNode root;
    record_node(0, kNoBuildNode, 0, data.root_box, all.data(), all.size());
    if (!build_node(main, 0, data.root_box, 0, all.data(), all.size(), 1.0, scratch, &root)) return error();
    main.nodes[0] = root;
    ACCEL_CHECK(main.nodes.size() % 8u == 1u);  // blocks of 8 after the root: octant = (id - 1) % 8
    data.nodes = std::move(main.nodes);
    data.prim_ids = std::move(main.prim_ids);
    data.parents = std::move(main.parents);
    data.depths = std::move(main.depths);
    data.reasons = main.reasons;
    sink_.done(octree_node_count(data));  // a quadtree's: the nodes its steps recorded
    return data;
  }

  Failure failure() const { return Failure(failure_.load(std::memory_order_relaxed)); }

 private:
  // Below this many triangles a node's children are built in its own task: their subtrees
  // are too small to pay for a task and a part of their own. The top-down driver's
  // threshold (top_down_tasks.h), whose pre-order chunks do not fit the octree's blocks of
  // eight children: its parts are spliced in octant order instead (splice()).
  static constexpr size_t kParallelChildren = top_down::kTaskMinRefs;
  // From this many triangles a node's child masks are computed in parallel.
  static constexpr size_t kParallelMasks = 16384;

  Error error() const {
    switch (failure()) {
      case Failure::Nodes: return limit_error("nodes", options_.node_limit);
      case Failure::References: return limit_error("triangle references", options_.reference_limit);
      case Failure::Memory:
        return make_error(driving_params_text() + ": " +
                          over_budget_text(memory_bytes(nodes_total_, refs_total_), options_.memory_limit) +
                          "; lower max_depth or raise max_prims");
      default: return cancelled_error();
    }
  }

  std::string driving_params_text() const {
    return "octree parameter 'max_depth' = " + std::to_string(options_.max_depth) +
           " (with max_prims = " + std::to_string(options_.max_prims) + ")";
  }

  /// What the build holds with `nodes` nodes and `refs` references: per triangle its
  /// OctreePrim, per node its entry, parent and depth, per reference an id -- twice, as a
  /// task's part is copied into its parent's when the two are spliced.
  double memory_bytes(size_t nodes, size_t refs) const {
    const double node_bytes = sizeof(OctreeNode) + sizeof(uint32_t) + sizeof(uint8_t);
    return double(scene_.triangle_count()) * sizeof(OctreePrim) +
           2.0 * (double(nodes) * node_bytes + double(refs) * sizeof(uint32_t));
  }
  bool over_memory() const { return memory_bytes(nodes_total_, refs_total_) > double(options_.memory_limit); }

  Error limit_error(const std::string& what, size_t limit) const {
    return make_error(driving_params_text() + ": would create more than " +
                      std::to_string(limit) + " " + what + " (what its 32-bit indices hold); lower max_depth or raise max_prims");
  }

  /// Records the first failure (any thread); every task stops at its next check.
  bool fail(Failure why) {
    int none = int(Failure::None);
    failure_.compare_exchange_strong(none, int(why), std::memory_order_relaxed);
    return false;
  }

  /// True when the build must stop: cancelled, or another task failed.
  bool stopping() {
    if (failure_.load(std::memory_order_relaxed) != int(Failure::None)) return true;
    if (build_cancelled(control_)) return !fail(Failure::Cancelled);
    return false;
  }

  /// Appends a node (a leaf until made inner) and its viewer data.
  static void add_node(OctreePart& part, uint32_t parent, int depth) {
    part.nodes.push_back(OctreeNode{});
    part.parents.push_back(parent);
    part.depths.push_back(uint8_t(depth));
  }

  /// Moves `child` (built by a task for the node `root_id` of `part`, whose value the task
  /// returned as `root`) to the end of `part`; returns the root's value in `part`'s numbering.
  static OctreeNode splice(OctreePart& part, uint32_t root_id, OctreePart&& child, OctreeNode root) {
    const uint32_t node_base = uint32_t(part.nodes.size()), prim_base = uint32_t(part.prim_ids.size());
    const auto relocate = [&](OctreeNode n) {
      n.first += n.leaf() ? prim_base : node_base;
      return n;
    };
    part.nodes.reserve(part.nodes.size() + child.nodes.size());
    for (const OctreeNode& n : child.nodes) part.nodes.push_back(relocate(n));
    part.parents.reserve(part.parents.size() + child.parents.size());
    for (uint32_t p : child.parents) part.parents.push_back(p == OctreePart::kPartRoot ? root_id : p + node_base);
    part.depths.insert(part.depths.end(), child.depths.begin(), child.depths.end());
    part.prim_ids.insert(part.prim_ids.end(), child.prim_ids.begin(), child.prim_ids.end());
    OctreeLeafReasons& r = part.reasons;
    const OctreeLeafReasons& c = child.reasons;
    r.few_prims += c.few_prims;
    r.max_depth += c.max_depth;
    r.no_gain += c.no_gain;
    r.inseparable += c.inseparable;
    r.tiny_box += c.tiny_box;
    return relocate(root);
  }

  /// Makes a leaf holding `prims` (its value to *out); `share` of the build is then done.
  bool make_leaf(OctreePart& part, const uint32_t* prims, size_t count, size_t* reason, double share,
                 OctreeNode* out) {
    if (stopping()) return false;  // a stuck child is made a leaf without build_node()'s check
    // The limit over all tasks: an over-limit reservation fails the build without allocating.
    if (refs_total_.fetch_add(count, std::memory_order_relaxed) + count > options_.reference_limit)
      return fail(Failure::References);
    if (over_memory()) return fail(Failure::Memory);
    *out = OctreeNode{uint32_t(part.prim_ids.size()), uint32_t(count)};
    part.prim_ids.insert(part.prim_ids.end(), prims, prims + count);
    ++*reason;
    leaves_done_.add_share(share);  // the build stops at its next stopping() check
    return true;
  }

  /// make_leaf() of node `id`, recording the leaf step (`why`) when it succeeds.
  ACCEL_FORCE_INLINE bool leaf(OctreePart& part, uint32_t id, LeafReason why, const uint32_t* prims, size_t count,
                               size_t* reason, double share, OctreeNode* out) {
    if (!make_leaf(part, prims, count, reason, share, out)) return false;
    if constexpr (Sink::kRecords) sink_.leaf(id, why, prims, count);
    return true;
  }

  /// Records node `id` (child of `parent`, at `depth`, box `box`) with its triangles. Every
  /// node is passed on (the recorder counts the depths below its limit); the centroid
  /// bounds are computed only for the nodes it keeps.
  void record_node(uint32_t id, uint32_t parent, int depth, const Aabb& box, const uint32_t* prims, size_t n) {
    if constexpr (Sink::kRecords) {
      Aabb centroids;
      if (sink_.records(depth))
        for (size_t k = 0; k < n; ++k) centroids.extend(scene_.centroid(prims[k]));
      sink_.node(id, parent, depth, box, centroids, prims, n);
    }
  }

  /// Octants (bits of a mask) of the children of `box` the triangle is assigned to.
  unsigned child_mask(uint32_t prim, const Aabb& box, const Vec3& mid) const {
    // The halves the triangle's bounding box reaches (it overlaps the node's box, or, for
    // exact insertion, its slightly enlarged box: then the flags still say which side).
    const OctreePrim& record = prims_[prim];
    const unsigned mask = octants_reached(record.bounds.min, record.bounds.max, mid) & octant_mask_;
    if (options_.insert == OctreeInsert::Bbox) return mask;
    const Vec3 &a = record.v[0], &b = record.v[1], &c = record.v[2];
    // A child holding a vertex (closed boxes) passes 12 of triangle_overlaps_box()'s 13 axes
    // whatever the rounding: the box axes and the 9 edge axes project all three vertices,
    // and that vertex lies inside the box's projection with the margins to spare. The plane
    // test projects only the first vertex: it passes alike where that one is inside, and
    // must run where only another is (see plane_overlaps()). The other children take the
    // full test.
    const auto holding = [&](const Vec3& p) {
      const bool inside = p.x >= box.min.x && p.x <= box.max.x && p.y >= box.min.y && p.y <= box.max.y &&
                          p.z >= box.min.z && p.z <= box.max.z;
      return inside ? octants_reached(p, p, mid) : 0u;
    };
    const unsigned certain = holding(a), holds_vertex = certain | holding(b) | holding(c);
    unsigned exact = certain & mask;
    for (unsigned rest = mask & ~certain; rest; rest &= rest - 1) {
      const unsigned octant = unsigned(std::countr_zero(rest));
      const Aabb child = octree_child_box(box, octant);
      const bool overlaps = (holds_vertex >> octant) & 1u ? plane_overlaps(centre_triangle(a, b, c, child))
                                                          : triangle_overlaps_box(a, b, c, child);
      if (overlaps) exact |= 1u << octant;
    }
    return exact;
  }

  /// A node being split into its 8 children: what building them needs.
  struct NodeSplit {
    uint32_t self;  // the node's id in its part
    const Aabb& box;
    int depth;
    size_t n;      // the node's triangles
    double share;  // its share of the progress
    size_t sizes[8] = {}, starts[8] = {}, refs = 0;  // the children's lists in `lists`
    const uint32_t* lists = nullptr;
    bool poor = false;  // references at least doubled
    Aabb bounds = {};   // of the node's triangles, only when a child keeps them all
  };

  /// Fills the node `self` of `part` (OctreePart::kPartRoot: the part's root; box `box`, at
  /// `depth`, `share` of the progress) with the `count` triangles at `prims`: a leaf, or an
  /// inner node whose 8 children are built recursively (depth <= 40, so recursion is
  /// shallow). Its value goes to *out.
  bool build_node(OctreePart& part, uint32_t self, const Aabb& box, int depth, const uint32_t* prims, size_t n,
                  double share, OctreeScratch& scratch, OctreeNode* out) {
    if (stopping()) return false;
    OctreeLeafReasons& why = part.reasons;
    if (n <= size_t(options_.max_prims))
      return leaf(part, self, LeafReason::FewPrims, prims, n, &why.few_prims, share, out);
    if (depth >= options_.max_depth) return leaf(part, self, LeafReason::MaxDepth, prims, n, &why.max_depth, share, out);
    const Vec3 mid = 0.5f * box.min + 0.5f * box.max;
    for (int axis = 0; axis < (planar_ ? 2 : 3); ++axis) {
      // At float resolution a half would equal the whole box: splitting cannot separate anything.
      if (mid[axis] <= box.min[axis] || mid[axis] >= box.max[axis])
        return leaf(part, self, LeafReason::TooThin, prims, n, &why.tiny_box, share, out);
    }
    // The children's lists, in the node's order, one after the other in this depth's buffer.
    std::vector<uint8_t>& masks = scratch.masks[depth];
    assign_octants(prims, n, box, mid, masks);
    NodeSplit split{.self = self, .box = box, .depth = depth, .n = n, .share = share};
    for (size_t k = 0; k < n; ++k)
      for (unsigned m = masks[k]; m; m &= m - 1) ++split.sizes[std::countr_zero(m)];
    for (unsigned octant = 0; octant < 8; ++octant)
      split.starts[octant] = split.refs, split.refs += split.sizes[octant];
    // No gain: each child has a quarter of the node's surface area (in 2D half its
    // perimeter), so a ray through the node passes 2 children on average and would test
    // refs/4 (refs/2) triangles instead of n, after visiting the node and those two children.
    if (3.0 * options_.ct + double(split.refs) * (planar_ ? 0.5 : 0.25) >= double(n))
      return leaf(part, self, LeafReason::NoGain, prims, n, &why.no_gain, share, out);
    std::vector<uint32_t>& lists = scratch.refs[depth];
    lists.resize(split.refs);
    size_t fill[8];
    std::copy(split.starts, split.starts + 8, fill);
    for (size_t k = 0; k < n; ++k)
      for (unsigned m = masks[k]; m; m &= m - 1) lists[fill[std::countr_zero(m)]++] = prims[k];
    split.lists = lists.data();
    if (!subdivide(part, self, depth, out)) return false;
    find_inseparable(split, prims);
    return build_children(part, split, out->first, scratch);
  }

  /// The octants each of the `n` triangles at `prims` goes to (child_mask()), into `masks`.
  void assign_octants(const uint32_t* prims, size_t n, const Aabb& box, const Vec3& mid, std::vector<uint8_t>& masks) {
    masks.resize(n);
    if (parallel_ && n >= kParallelMasks) {
      par::parallel_for(par::blocked_range<size_t>(0, n, 1024), [&](const par::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k) masks[k] = uint8_t(child_mask(prims[k], box, mid));
      });
    } else {
      // The records are read in the list's order, scattered over the scene: fetch ahead.
      constexpr size_t kAhead = 8;
      for (size_t k = 0; k < n; ++k) {
        if (k + kAhead < n) __builtin_prefetch(&prims_[prims[k + kAhead]]);
        masks[k] = uint8_t(child_mask(prims[k], box, mid));
      }
    }
  }

  /// Appends the 8 children of node `self` (within the node limit and the memory budget),
  /// makes it inner (*out) and records the step.
  bool subdivide(OctreePart& part, uint32_t self, int depth, OctreeNode* out) {
    if (nodes_total_.fetch_add(8, std::memory_order_relaxed) + 8 > options_.node_limit) return fail(Failure::Nodes);
    if (over_memory()) return fail(Failure::Memory);
    const uint32_t first = uint32_t(part.nodes.size());
    for (int k = 0; k < 8; ++k) add_node(part, self, depth + 1);
    *out = OctreeNode{first, OctreeNode::kInner};
    if constexpr (Sink::kRecords) {
      uint32_t children[8];
      for (uint32_t k = 0; k < 8; ++k) children[k] = first + k;
      sink_.subdivide(self, children, planar_ ? 4u : 8u);  // a quadtree's four (octree_child_count)
    }
    return true;
  }

  /// A child that keeps all n triangles is split again only while that can still separate
  /// them: not after a poor split (references at least doubled: the triangles spread over
  /// the children, as around a shared vertex or edge), and not when the triangles' bounds
  /// cover the whole child (they all pass through it, e.g. meet at a point inside it).
  /// A compact cluster in a big cell (the teapot in the stadium) is neither: it is
  /// refined until the cells are small enough to separate its triangles.
  void find_inseparable(NodeSplit& split, const uint32_t* prims) const {
    split.poor = split.refs >= 2 * split.n;
    for (unsigned octant = 0; octant < 8; ++octant) {
      if (split.sizes[octant] == split.n && !split.poor) {
        for (size_t k = 0; k < split.n; ++k) split.bounds.extend(prims_[prims[k]].bounds);
        break;
      }
    }
  }

  /// Child `octant` of the split node into `into`, whose node `id` it is; its value to *value.
  bool build_child(const NodeSplit& split, unsigned octant, OctreePart& into, uint32_t id, OctreeScratch& scratch,
                   OctreeNode* value) {
    const uint32_t* child = split.lists + split.starts[octant];
    const size_t size = split.sizes[octant];
    const Aabb child_box = octree_child_box(split.box, octant);
    const bool stuck = size == split.n && (split.poor || split.bounds.contains(child_box));
    // No child took a triangle (exact insertion over triangles that touch no child's box
    // interior, clang's UBSan caught the 0/0): the eight share the node's part evenly.
    const double child_share = split.refs > 0 ? split.share * double(size) / double(split.refs) : split.share / 8.0;
    // A quadtree's upper-z octants hold nothing and are no part of the lecture's figure:
    // empty leaves as the build would make them, without construction steps.
    if (planar_ && octant >= 4) return make_leaf(into, child, 0, &into.reasons.few_prims, child_share, value);
    record_node(id, split.self, split.depth + 1, child_box, child, size);
    return stuck ? leaf(into, id, LeafReason::NoProgress, child, size, &into.reasons.inseparable, child_share, value)
                 : build_node(into, id, child_box, split.depth + 1, child, size, child_share, scratch, value);
  }

  /// The 8 children (nodes first..first + 7 of `part`) in octant order; for a node of many
  /// triangles as 8 tasks, each into its own part, spliced in octant order.
  bool build_children(OctreePart& part, const NodeSplit& split, uint32_t first, OctreeScratch& scratch) {
    if (!parallel_ || split.n < kParallelChildren) {
      for (unsigned octant = 0; octant < 8; ++octant) {
        OctreeNode value;
        if (!build_child(split, octant, part, first + octant, scratch, &value)) return false;
        part.nodes[first + octant] = value;
      }
      return true;
    }
    std::array<OctreePart, 8> parts;
    std::array<OctreeNode, 8> values;
    std::atomic<bool> ok{true};
    par::parallel_for(0u, 8u, [&](unsigned octant) {
      OctreeScratch own;  // the lists of this depth belong to the waiting parent
      if (!build_child(split, octant, parts[octant], OctreePart::kPartRoot, own, &values[octant]))
        ok.store(false, std::memory_order_relaxed);
    });
    if (!ok.load(std::memory_order_relaxed)) return false;
    for (unsigned octant = 0; octant < 8; ++octant)
      part.nodes[first + octant] = splice(part, first + octant, std::move(parts[octant]), values[octant]);
    return true;
  }

  const Scene& scene_;
  const OctreeBuildOptions& options_;
  BuildControl* control_;
  const bool parallel_;
  const bool planar_ = scene_.planar();                   // a 2D scene: split x and y only (a quadtree)
  const unsigned octant_mask_ = planar_ ? 0x0Fu : 0xFFu;  // the octants that may hold triangles
  Sink& sink_;
  std::vector<OctreePrim> prims_;        // by triangle id (valid ones only filled)
  ProgressSpan progress_;                // reported through leaves_done_ only
  ProgressCounter leaves_done_;          // the shares of the build in finished leaves (any thread)
  std::atomic<size_t> nodes_total_{0};   // nodes reserved by all tasks
  std::atomic<size_t> refs_total_{0};    // triangle references reserved by all tasks
  std::atomic<int> failure_{int(Failure::None)};
};

}  // namespace

Result<OctreeData> build_octree(const Scene& scene, const OctreeBuildOptions& options, BuildControl* control,
                                BuildRecorder* recorder) {
  ACCEL_CHECK(options.max_depth >= 0 && options.max_depth <= kOctreeMaxDepth);
  ACCEL_CHECK(options.max_prims >= 1);
  // Recorded: serially (the same tree, node ids and all), so one run names any limit too.
  if (recorder) return OctreeBuilder<BuildRecorder>(scene, options, control, false, *recorder).run();
  NullBuildSink sink;
  using Builder = OctreeBuilder<NullBuildSink>;
  Builder parallel(scene, options, control, true, sink);
  auto built = parallel.run();
  if (built || parallel.failure() == Builder::Failure::Cancelled) return built;
  // Over a limit. Whether the build fails does not depend on the order (the totals only
  // grow), but which limit is met first does: the serial build names it as it always did.
  return Builder(scene, options, control, false, sink).run();
}

// [SECTION] Structure

const ParamTable<OctreeOptions>& Octree::param_table() {
  using O = OctreeOptions;
  static const auto table =
      ParamTable<O>(O::planar_defaults())
          .integer("max_prims", [](O& o) -> auto& { return o.build.max_prims; }, 1, 4096,
                   "a cell holding at most this many triangles is not subdivided (2D scenes: 1 by default, the "
                   "lecture's quadtree)")
          .integer("max_depth", [](O& o) -> auto& { return o.build.max_depth; }, 0, kOctreeMaxDepth,
                   "deepest level of subdivision (the root is level 0)")
          .choice("insert", [](O& o) -> auto& { return o.build.insert; },
                  std::vector<std::pair<std::string, OctreeInsert>>{{"bbox", OctreeInsert::Bbox},
                                                                   {"exact", OctreeInsert::Exact}},
                  "a triangle goes to each child its bounding box (bbox) or the triangle itself (exact) overlaps")
          .number("ct", [](O& o) -> auto& { return o.build.ct; }, 0, 100,
                  "cost of a node visit in triangle tests: a cell is split only when 3 ct + its children's "
                  "references / 4 < its triangles (0 = references < 4 x triangles). 2D scenes: 0 by default "
                  "(references / 2 < triangles), since with 2 no split of a few triangles pays and the "
                  "blackboard's ten stay one leaf")
          .choice("order", &O::order,
                  std::vector<std::pair<std::string, OctreeOrder>>{{"sorted", OctreeOrder::Sorted},
                                                                  {"fixed", OctreeOrder::Fixed}},
                  "children visited front to back along the ray (sorted) or in octant order 0..7 (fixed)");
  return table;
}

Status Octree::build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) {
  scene_ = &scene;
  OctreeOptions all = param_table().apply(params);
  all.build.memory_limit = build_memory_limit(control);
  const OctreeBuildOptions& options = all.build;
  order_ = all.order;
  auto built = build_octree(scene, options, control, recorder);
  if (!built) {
    data_ = OctreeData{};
    stats_ = BuildStats{};
    return built.error();
  }
  data_ = std::move(built.value());

  // Statistics, once: the expected cost with ct = ci = 1 (each visited inner node costs ct,
  // each triangle of a visited leaf ci), weighted by the probability area(node)/area(root)
  // that a random ray through the root also passes the node.
  BuildStats s;
  s.prims = scene.valid_prims().size();
  // A quadtree counts its four children per node, as node_children() lists them.
  s.nodes = octree_node_count(data_);
  s.prim_references = data_.prim_ids.size();
  s.memory_bytes = data_.nodes.size() * sizeof(OctreeNode) + data_.prim_ids.size() * sizeof(uint32_t);
  s.sah_ct = 1.0;
  s.sah_ci = 1.0;
  double cost = 0.0;
  size_t inner = 0;
  for (size_t id = 0; id < data_.nodes.size(); ++id) {
    if (octree_unused_octant(data_, id)) continue;  // empty: no cost either
    const OctreeNode& n = data_.nodes[id];
    // Children have 1/4 of the area (a quadtree's 1/2 of the perimeter).
    const double area = std::ldexp(1.0, -(data_.planar ? 1 : 2) * data_.depths[id]);
    if (n.leaf()) {
      s.add_leaf(n.count);
      s.max_depth = std::max(s.max_depth, int(data_.depths[id]));
      cost += s.sah_ci * n.count * area;
    } else {
      ++inner;
      cost += s.sah_ct * area;
    }
  }
  s.sah_cost = cost;
  const Vec3 side = data_.root_box.extent();
  const OctreeLeafReasons& r = data_.reasons;
  s.extra = {
      {data_.planar ? "root square side" : "root cube side", std::to_string(std::max(side.x, std::max(side.y, side.z)))},
      {"inner nodes", std::to_string(inner)},
      {"leaves by stop reason",
       "few prims " + std::to_string(r.few_prims) + ", max depth " + std::to_string(r.max_depth) + ", no gain " +
           std::to_string(r.no_gain) + ", inseparable " + std::to_string(r.inseparable) + ", tiny box " +
           std::to_string(r.tiny_box)},
      {"viewer parent links bytes", std::to_string(data_.parents.size() * (sizeof(uint32_t) + sizeof(uint8_t)))},
      {"insert", params.get_choice("insert")},
      {"order", params.get_choice("order")},
  };
  stats_ = std::move(s);
  return {};
}

void Octree::for_each_node(const std::function<void(const NodeView&)>& fn) const {
  // Ids grow from parent to child, so one pass in id order derives every box from its
  // parent's, already known.
  std::vector<Aabb> boxes(data_.nodes.size());
  if (!boxes.empty()) boxes[0] = data_.root_box;
  for (size_t id = 0; id < data_.nodes.size(); ++id) {
    const OctreeNode& n = data_.nodes[id];
    NodeView v;
    v.id = NodeId(id);
    v.depth = data_.depths[id];
    v.leaf = n.leaf();
    v.prim_count = n.leaf() ? n.count : 0;
    v.box = boxes[id];
    if (!n.leaf())
      for (unsigned octant = 0; octant < 8; ++octant) boxes[n.first + octant] = octree_child_box(boxes[id], octant);
    if (octree_unused_octant(data_, id)) continue;
    fn(v);
  }
}

NodeView Octree::node_view(NodeId id) const {
  NodeView v;
  if (id >= data_.nodes.size()) return v;
  // Walk up to the root collecting octants, then halve the root box back down.
  unsigned octants[kOctreeMaxDepth + 1];
  int depth = 0;
  for (NodeId n = id; n != 0; n = data_.parents[n]) octants[depth++] = (n - 1u) & 7u;
  Aabb box = data_.root_box;
  for (int level = depth - 1; level >= 0; --level) box = octree_child_box(box, octants[level]);
  const OctreeNode& n = data_.nodes[id];
  v.id = id;
  v.depth = depth;
  v.leaf = n.leaf();
  v.prim_count = n.leaf() ? n.count : 0;
  v.box = box;
  return v;
}

std::vector<uint32_t> Octree::node_prims(NodeId id) const {
  if (id >= data_.nodes.size() || !data_.nodes[id].leaf()) return {};
  const OctreeNode& n = data_.nodes[id];
  return {data_.prim_ids.begin() + n.first, data_.prim_ids.begin() + n.first + n.count};
}

std::vector<NodeId> Octree::node_children(NodeId id) const {
  if (id >= data_.nodes.size() || data_.nodes[id].leaf()) return {};
  std::vector<NodeId> children;
  for (uint32_t octant = 0; octant < octree_child_count(data_); ++octant) children.push_back(data_.nodes[id].first + octant);
  return children;
}

}  // namespace accel
