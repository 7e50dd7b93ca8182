#include "structures/octree.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace accel {

// [SECTION] Geometry: root cube, triangle/box overlap

Aabb octree_root_box(const Aabb& bounds) {
  if (bounds.empty()) return bounds;
  // In double: max - min of floats near the float range would overflow in float.
  double side = 0.0;
  for (int axis = 0; axis < 3; ++axis) side = std::max(side, double(bounds.max[axis]) - double(bounds.min[axis]));
  Aabb box;
  for (int axis = 0; axis < 3; ++axis) {
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

bool triangle_overlaps_box(const Vec3& a, const Vec3& b, const Vec3& c, const Aabb& box) {
  // Akenine-Moller 2001: the triangle and the box are disjoint iff one of 13 axes separates
  // them: the 3 box normals, the triangle normal and the 9 cross products of box normals
  // and triangle edges. Everything relative to the box centre, in double.
  const DVec3 centre = 0.5 * (DVec3(box.min) + DVec3(box.max));
  const DVec3 v0 = DVec3(a) - centre, v1 = DVec3(b) - centre, v2 = DVec3(c) - centre;
  const DVec3 reach = glm::max(glm::abs(v0), glm::max(glm::abs(v1), glm::abs(v2)));
  const double far = std::max(reach.x, std::max(reach.y, reach.z));
  // Enlarged half size: double rounding of the products below is ~2^-52 of |v| and |h|, far
  // below these margins, so a triangle touching the closed box is always kept.
  const DVec3 h = 0.5 * (DVec3(box.max) - DVec3(box.min)) * (1.0 + 0x1p-20) + DVec3(far * 0x1p-40);

  // 1. Box normals: the triangle's bounding box against the box.
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = std::min(v0[axis], std::min(v1[axis], v2[axis]));
    const double hi = std::max(v0[axis], std::max(v1[axis], v2[axis]));
    if (lo > h[axis] || hi < -h[axis]) return false;
  }
  // 2. The 9 axes e_axis x edge. For axis x and edge f the axis is (0, -f.z, f.y); the
  // projections of the three vertices take two distinct values, the box's radius is
  // h.y*|f.z| + h.z*|f.y|.
  const DVec3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
  const DVec3* verts[3] = {&v0, &v1, &v2};
  for (const DVec3& f : edges) {
    for (int axis = 0; axis < 3; ++axis) {
      const int i = (axis + 1) % 3, j = (axis + 2) % 3;
      // axis vector: component i = -f[j], component j = f[i]
      double lo = INFINITY, hi = -INFINITY;
      for (const DVec3* v : verts) {
        const double p = -f[j] * (*v)[i] + f[i] * (*v)[j];
        lo = std::min(lo, p);
        hi = std::max(hi, p);
      }
      const double r = h[i] * std::abs(f[j]) + h[j] * std::abs(f[i]);
      if (lo > r || hi < -r) return false;
    }
  }
  // 3. The triangle's plane against the box: the box's projected radius onto the normal.
  const DVec3 n = glm::cross(v1 - v0, v2 - v0);
  const double d = glm::dot(n, v0);
  const double r = h.x * std::abs(n.x) + h.y * std::abs(n.y) + h.z * std::abs(n.z);
  return std::abs(d) <= r;
}

// [SECTION] Builder

namespace {

/// Top-down octree builder (lecture: "start with the bbox of the whole scene, subdivide a
/// cell into 8 equal sub-cells; stopping criterion: the number of objects, and maximal
/// depth"), plus the stops of build_octree()'s contract that keep extreme settings bounded.
class OctreeBuilder {
 public:
  OctreeBuilder(const Scene& scene, const OctreeBuildOptions& options, BuildControl* control)
      : scene_(scene), options_(options), control_(control), progress_(control, 0.0, 1.0) {}

  Result<OctreeData> run() {
    Aabb bounds;
    for (uint32_t prim : scene_.valid_prims()) bounds.extend(scene_.triangle_bounds(prim));
    data_.root_box = octree_root_box(bounds);
    add_node(kNoNode, 0);
    if (!build_node(0, data_.root_box, 0, scene_.valid_prims(), 1.0)) return error_;
    return std::move(data_);
  }

 private:
  /// Appends a node (a leaf until made inner) and its viewer data.
  void add_node(uint32_t parent, int depth) {
    data_.nodes.push_back(OctreeNode{});
    data_.parents.push_back(parent);
    data_.depths.push_back(uint8_t(depth));
  }

  bool fail(const std::string& what, size_t limit) {
    error_ = make_error("octree parameter 'max_depth' = " + std::to_string(options_.max_depth) +
                        " (with max_prims = " + std::to_string(options_.max_prims) + "): would create more than " +
                        std::to_string(limit) + " " + what + " (the build's memory limit); lower max_depth or raise max_prims");
    return false;
  }

  /// Makes node `id` a leaf holding `prims`; `share` of the build is then done.
  bool make_leaf(uint32_t id, const std::vector<uint32_t>& prims, size_t* reason, double share) {
    if (build_cancelled(control_)) {  // a stuck child is made a leaf without build_node()'s check
      error_ = cancelled_error();
      return false;
    }
    if (data_.prim_ids.size() + prims.size() > options_.reference_limit)
      return fail("triangle references", options_.reference_limit);
    data_.nodes[id] = OctreeNode{uint32_t(data_.prim_ids.size()), uint32_t(prims.size())};
    data_.prim_ids.insert(data_.prim_ids.end(), prims.begin(), prims.end());
    ++*reason;
    done_ += share;
    progress_.advance(done_);
    return true;
  }

  /// Octants (bits of a mask) of the children of `box` the triangle is assigned to.
  unsigned child_mask(uint32_t prim, const Aabb& box, const Vec3& mid) const {
    // Per axis, the halves the triangle's bounding box reaches (it overlaps the node's box,
    // or, for exact insertion, its slightly enlarged box: then the flags still say which
    // side). Closed intervals: a triangle touching the split plane goes to both sides.
    const Aabb& tb = scene_.triangle_bounds(prim);
    unsigned mask = 0xFFu;
    for (int axis = 0; axis < 3; ++axis) {
      const bool lower = tb.min[axis] <= mid[axis], upper = tb.max[axis] >= mid[axis];
      unsigned keep = 0;
      for (unsigned octant = 0; octant < 8; ++octant) {
        const bool is_upper = (octant >> axis) & 1u;
        if (is_upper ? upper : lower) keep |= 1u << octant;
      }
      mask &= keep;
    }
    if (options_.insert == OctreeInsert::Bbox) return mask;
    unsigned exact = 0;
    for (unsigned octant = 0; octant < 8; ++octant) {
      if (((mask >> octant) & 1u) &&
          triangle_overlaps_box(scene_.vertex(prim, 0), scene_.vertex(prim, 1), scene_.vertex(prim, 2),
                                octree_child_box(box, octant)))
        exact |= 1u << octant;
    }
    return exact;
  }

  /// Fills node `id` (box `box`, at `depth`, `share` of the progress) with `prims`: a leaf,
  /// or an inner node whose 8 children are built recursively (depth <= 40, so recursion is
  /// shallow).
  bool build_node(uint32_t id, const Aabb& box, int depth, const std::vector<uint32_t>& prims, double share) {
    if (build_cancelled(control_)) {
      error_ = cancelled_error();
      return false;
    }
    OctreeLeafReasons& why = data_.reasons;
    if (prims.size() <= size_t(options_.max_prims)) return make_leaf(id, prims, &why.few_prims, share);
    if (depth >= options_.max_depth) return make_leaf(id, prims, &why.max_depth, share);
    const Vec3 mid = 0.5f * box.min + 0.5f * box.max;
    for (int axis = 0; axis < 3; ++axis) {
      // At float resolution a half would equal the whole box: splitting cannot separate anything.
      if (mid[axis] <= box.min[axis] || mid[axis] >= box.max[axis]) return make_leaf(id, prims, &why.tiny_box, share);
    }

    std::array<std::vector<uint32_t>, 8> children;
    for (uint32_t prim : prims) {
      const unsigned mask = child_mask(prim, box, mid);
      for (unsigned octant = 0; octant < 8; ++octant)
        if ((mask >> octant) & 1u) children[octant].push_back(prim);
    }
    const size_t n = prims.size();
    size_t refs = 0;
    for (const auto& child : children) refs += child.size();
    // No gain: each child has a quarter of the node's surface area, so a ray through the
    // node passes 2 children on average and would test refs/4 triangles instead of n.
    if (refs >= 4 * n) return make_leaf(id, prims, &why.no_gain, share);

    if (data_.nodes.size() + 8 > options_.node_limit) return fail("nodes", options_.node_limit);
    const uint32_t first = uint32_t(data_.nodes.size());
    ACCEL_CHECK((first - 1u) % 8u == 0u);  // blocks of 8 after the root: octant = (id - 1) % 8
    for (int k = 0; k < 8; ++k) add_node(id, depth + 1);
    data_.nodes[id] = OctreeNode{first, OctreeNode::kInner};
    // A child that keeps all n triangles is split again only while that can still separate
    // them: not after a poor split (references at least doubled: the triangles spread over
    // the children, as around a shared vertex or edge), and not when the triangles' bounds
    // cover the whole child (they all pass through it, e.g. meet at a point inside it).
    // A compact cluster in a big cell (the teapot in the stadium) is neither: it is
    // refined until the cells are small enough to separate its triangles.
    const bool poor = refs >= 2 * n;
    Aabb bounds;  // of the node's triangles, needed only when a child keeps them all
    for (const auto& child : children) {
      if (child.size() == n && !poor) {
        for (uint32_t prim : prims) bounds.extend(scene_.triangle_bounds(prim));
        break;
      }
    }
    for (unsigned octant = 0; octant < 8; ++octant) {
      std::vector<uint32_t> child = std::move(children[octant]);
      const uint32_t child_id = first + octant;
      const Aabb child_box = octree_child_box(box, octant);
      const bool stuck = child.size() == n && (poor || bounds.contains(child_box));
      const double child_share = share * double(child.size()) / double(refs);
      const bool ok = stuck ? make_leaf(child_id, child, &why.inseparable, child_share)
                            : build_node(child_id, child_box, depth + 1, child, child_share);
      if (!ok) return false;
    }
    return true;
  }

  const Scene& scene_;
  const OctreeBuildOptions& options_;
  BuildControl* control_;
  ProgressSpan progress_;
  double done_ = 0.0;  // share of the build in finished leaves
  OctreeData data_;
  Error error_;
};

}  // namespace

Result<OctreeData> build_octree(const Scene& scene, const OctreeBuildOptions& options, BuildControl* control) {
  ACCEL_CHECK(options.max_depth >= 0 && options.max_depth <= kOctreeMaxDepth);
  ACCEL_CHECK(options.max_prims >= 1);
  return OctreeBuilder(scene, options, control).run();
}

// [SECTION] Structure

const ParamTable<OctreeOptions>& Octree::param_table() {
  using O = OctreeOptions;
  static const auto table =
      ParamTable<O>()
          .integer("max_prims", [](O& o) -> auto& { return o.build.max_prims; }, 1, 4096,
                   "a cell holding at most this many triangles is not subdivided")
          .integer("max_depth", [](O& o) -> auto& { return o.build.max_depth; }, 0, kOctreeMaxDepth,
                   "deepest level of subdivision (the root is level 0)")
          .choice("insert", [](O& o) -> auto& { return o.build.insert; },
                  std::vector<std::pair<std::string, OctreeInsert>>{{"bbox", OctreeInsert::Bbox},
                                                                   {"exact", OctreeInsert::Exact}},
                  "a triangle goes to each child its bounding box (bbox) or the triangle itself (exact) overlaps")
          .choice("order", &O::order,
                  std::vector<std::pair<std::string, OctreeOrder>>{{"sorted", OctreeOrder::Sorted},
                                                                  {"fixed", OctreeOrder::Fixed}},
                  "children visited front to back along the ray (sorted) or in octant order 0..7 (fixed)");
  return table;
}

Status Octree::build_impl(const Scene& scene, const ParamSet& params, BuildControl* control) {
  scene_ = &scene;
  const OctreeOptions all = param_table().apply(params);
  const OctreeBuildOptions& options = all.build;
  order_ = all.order;
  auto built = build_octree(scene, options, control);
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
  s.nodes = data_.nodes.size();
  s.prim_references = data_.prim_ids.size();
  s.memory_bytes = data_.nodes.size() * sizeof(OctreeNode) + data_.prim_ids.size() * sizeof(uint32_t);
  s.sah_ct = 1.0;
  s.sah_ci = 1.0;
  double cost = 0.0;
  size_t inner = 0;
  for (size_t id = 0; id < data_.nodes.size(); ++id) {
    const OctreeNode& n = data_.nodes[id];
    const double area = std::ldexp(1.0, -2 * data_.depths[id]);  // children have 1/4 of the area
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
      {"root cube side", std::to_string(std::max(side.x, std::max(side.y, side.z)))},
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

}  // namespace accel
