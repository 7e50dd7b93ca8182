// Assignment: the KD-TREE of the lecture ("kD-Tree"): axis-aligned split planes, traversed
// with the lecture's near/far recursion and its three cases. Fill in build() and intersect()
// where it says TODO; the log calls are already where the lecture's steps happen (keep them
// there: the viewer animates them and `check` reads them). As it stands the root is one
// empty leaf and every ray misses.
//
// Build it into accelviz and check it:
//   scripts/run.sh --student student/skeletons/kdtree
//   build/bin/accelviz-cli check --structure my_kdtree
// The kit's reference: student/accelviz_student.h; a complete example: student/example/.
//
// The lecture's traversal, which intersect() below runs with a stack of deferred far children:
//   traverse(r, n, t_min, t_max):
//     if n is leaf: intersect r with each primitive, return the closest hit (if any)
//     t_split = signed distance along r to the splitting plane of n
//     near = child of n containing origin of r;  far = the "other" child
//     if t_split > t_max: return traverse(r, near, t_min, t_max)       // (b)
//     else if t_split < t_min: return traverse(r, far, t_min, t_max)   // (c)
//     else:                                                            // (a)
//       t_hit = traverse(r, near, t_min, t_split)
//       if t_hit < t_split: return t_hit                                // early exit
//       return traverse(r, far, t_split, t_max)
#include <algorithm>
#include <cmath>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class MyKdTree : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    scene_ = &scene;
    nodes_.clear();
    // TODO 1: the root: the triangles that are not degenerate (scene.is_degenerate(p)), and
    //         the box around them ("at the root, the box encloses the whole universe").
    std::vector<uint32_t> prims;
    root_box_ = scene.bounds();
    build_node(root_box_, prims, kNoParent, 0, log);
  }

  Hit intersect(const Ray& ray, TraversalLog log) const override {
    Hit closest;
    closest.t = ray.tmax;  // closest_hit: at first "as far as the ray goes"
    if (nodes_.empty()) return finish(closest);
    // "Intersect ray with root-box -> t_min, t_max"
    float t_min = 0.0f, t_max = 0.0f;
    if (!intersect_box(ray, root_box_, ray.tmin, ray.tmax, t_min, t_max)) {
      log.cull(0, 0, Cull::MissedBounds);
      return finish(closest);
    }
    struct Entry {  // a deferred far child and its interval [t_split, t_max]
      uint32_t node;
      int depth;
      float t_min, t_max;
    };
    std::vector<Entry> stack;  // (a fixed array of kMaxDepth entries is faster)
    uint32_t id = 0;
    int depth = 0;
    for (;;) {
      const Node& n = nodes_[id];
      log.visit(id, depth, t_min, t_max);
      if (!n.leaf) {
        // TODO 2: t_split = (n.split - o[axis]) * inv_direction[axis]; near = the child the ray
        //         is in before t_split, far = the other. Mind d[axis] == +-0 (t_split is +-inf,
        //         or NaN when the ray lies in the plane: then visit both children).
        const float t_split = kInfinity;
        const uint32_t near = n.left, far = n.right;
        log.kd_split(t_min, t_split, t_max, near, far, n.axis);
        // TODO 3: which of the three cases applies (and mind rounding: when t_split is about
        //         t_min or t_max, visiting both children is the safe choice).
        const bool case_b = true;   // (b) t_split > t_max: the near child only
        const bool case_c = false;  // (c) t_split < t_min: the far child only
        ++depth;
        if (case_b) {
          log.cull(far, depth, Cull::MissedBounds, t_split);
          id = near;
        } else if (case_c) {
          log.cull(near, depth, Cull::MissedBounds, t_split);
          id = far;
        } else {  // (a) near now over [t_min, t_split], far later over [t_split, t_max]
          // (std::max / std::min in this order keep [t_min, t_max] when t_split is NaN)
          stack.push_back({far, depth, std::max(t_min, t_split), t_max});
          log.push(far, depth, std::max(t_min, t_split));
          t_max = std::min(t_max, t_split);
          id = near;
        }
        continue;
      }
      // A leaf: "intersect r with each primitive" (a hit may lie beyond this leaf's t_max).
      for (uint32_t p : n.prims) test_triangle(ray, *scene_, p, closest, log);
      // Next: the most recently deferred far child, unless the early exit applies.
      bool more = false;
      while (!stack.empty() && !more) {
        const Entry e = stack.back();
        stack.pop_back();
        log.pop(e.node, e.depth, e.t_min);
        // TODO 4: the early exit "if t_hit < t_split: return t_hit": only a hit found BEFORE
        //         the far child's t_split (e.t_min) ends the search -- a hit beyond it may be
        //         beaten by a triangle in the far child.
        const bool exits = false;
        log.kd_far_pop(closest.t, e.t_min, e.node, exits);
        if (exits) {
          log.cull(e.node, e.depth, Cull::BeyondClosestHit, e.t_min);
          continue;
        }
        id = e.node, depth = e.depth, t_min = e.t_min, t_max = e.t_max;
        more = true;
      }
      if (!more) break;
    }
    return finish(closest);
  }

 private:
  static constexpr size_t kMaxLeaf = 4;  // a node with at most this many triangles is a leaf
  static constexpr int kMaxDepth = 24;   // e.g. pbrt's 8 + 1.3 log2(N)

  struct Node {
    bool leaf = true;
    int axis = 0;                  // the split plane: axis ...
    float split = 0.0f;            // ... and position
    uint32_t left = 0, right = 0;  // the children: below and above the plane
    std::vector<uint32_t> prims;   // a leaf's triangles
  };

  uint32_t build_node(const Box& region, const std::vector<uint32_t>& prims, uint32_t parent, int depth,
                      BuildLog& log) {
    const uint32_t id = uint32_t(nodes_.size());
    nodes_.push_back(Node{});
    log.node(id, parent, depth, region, prims);
    // TODO 5: the stopping criterion: few triangles or depth >= kMaxDepth -> a leaf (drop the
    //         "true ||"). (TODO 6 may make one too, after choosing the split.)
    if (true || prims.size() <= kMaxLeaf || depth >= kMaxDepth) {
      nodes_[id].prims = prims;
      log.leaf(id, prims, prims.size() <= kMaxLeaf ? LeafWhy::FewTriangles : LeafWhy::MaxDepth);
      return id;
    }
    // TODO 6: "1. Choose an axis-aligned plane, with which to split the cell" (e.g. the middle
    //         of the region's longest axis), "2. Distribute the geometry among the two
    //         children": a triangle whose box touches or straddles the plane goes to BOTH; the
    //         children's regions are the region cut at the plane.
    const int axis = 0;
    const float position = region.center()[axis];
    std::vector<uint32_t> left, right;
    Box left_region = region, right_region = region;
    const float cost = 0.0f;  // C(B) of this split, against the leaf's cost prims.size()
    // TODO 6 (cont.): a leaf after all when the split separates little (identical or heavily
    //         overlapping triangles go to both sides again and again: LeafWhy::NoProgress)
    //         or costs more than the leaf (LeafWhy::NoGain): nodes_[id].prims = prims,
    //         log.leaf(id, prims, why), return id.
    log.split(id, axis, position, cost, float(prims.size()), uint32_t(left.size()), uint32_t(right.size()));
    // "3. Do a recursion"
    const uint32_t l = build_node(left_region, left, id, depth + 1, log);
    const uint32_t r = build_node(right_region, right, id, depth + 1, log);
    Node& node = nodes_[id];  // only now: nodes_ grew in the recursion (references go stale)
    node.leaf = false, node.axis = axis, node.split = position, node.left = l, node.right = r;
    return id;
  }

  const Scene* scene_ = nullptr;
  Box root_box_;
  std::vector<Node> nodes_;
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(MyKdTree, "my_kdtree", kdtree)
