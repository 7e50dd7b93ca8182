// Lecturer's test solution: the octree of the lecture ("Octree"), written the way a student
// would: the scene's box split into 8 equal children while a node holds more than a few
// triangles, a triangle going to every child its bounding box touches; the traversal visits
// the children the ray hits front to back with a stack and skips every node that starts
// beyond the closest hit so far (the lecture's OctreeNode::Trace).
//
// Planted bug (off by default), compiled as a variant by the kit's tests:
//   PLANT_BUG_OCTREE_BOUNDARY  a triangle goes to a child only when its box overlaps the
//                              child's with STRICT inequalities, so a triangle lying in a
//                              child's boundary plane (an axis-aligned wall, a flat scene) is
//                              lost from one or all children.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "accelviz_student.h"

#ifndef SOLUTION_NAME
#define SOLUTION_NAME "sol_octree"
#endif

using namespace accelviz;

namespace {

class SolutionOctree : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    scene_ = &scene;
    nodes_.clear();
    std::vector<uint32_t> prims;
    Box box;
    for (uint32_t p = 0; p < scene.size(); ++p) {
      if (scene.is_degenerate(p)) continue;  // zero-area: never hit
      prims.push_back(p);
      box.grow(scene.box(p));
    }
    if (prims.empty()) return;  // an empty tree: every ray misses
    build_node(box, prims, kNoParent, 0, log);
  }

  Hit intersect(const Ray& ray, TraversalLog log) const override {
    Hit closest;
    closest.t = ray.tmax;
    if (nodes_.empty()) return finish(closest);
    float t_enter, t_exit;
    if (!intersect_box(ray, nodes_[0].box, ray.tmin, ray.tmax, t_enter, t_exit)) {
      log.cull(0, 0, Cull::MissedBounds);
      return finish(closest);
    }
    struct Entry {
      uint32_t node;
      float t_enter, t_exit;
    };
    // Each inner node on the path leaves at most 7 children pending.
    Entry stack[8 * (kMaxDepth + 1)];
    int size = 0;
    stack[size++] = {0, t_enter, t_exit};
    log.push(0, 0, t_enter);
    // The children's visiting order: octant i ^ mask, where mask has a bit for each axis
    // the ray runs down (negative direction): front to back along the ray.
    const unsigned mask = (ray.direction.x < 0.0f ? 1u : 0u) | (ray.direction.y < 0.0f ? 2u : 0u) |
                          (ray.direction.z < 0.0f ? 4u : 0u);
    while (size > 0) {
      const Entry e = stack[--size];
      const Node& n = nodes_[e.node];
      log.pop(e.node, n.depth, e.t_enter);
      // "if a collision has already been detected and it's closer than the ray entry point
      // into this node: return"
      if (e.t_enter > closest.t) {
        log.cull(e.node, n.depth, Cull::BeyondClosestHit, e.t_enter);
        continue;
      }
      log.visit(e.node, n.depth, e.t_enter, e.t_exit);
      if (n.leaf) {
        for (uint32_t p : n.prims) test_triangle(ray, *scene_, p, closest, log);
        continue;
      }
      OctreeChild order[8];
      for (int i = 0; i < 8; ++i) {
        OctreeChild& c = order[i];
        c.octant = int(unsigned(i) ^ mask);
        c.node = n.child[c.octant];
        if (c.node == kNoParent) {
          c.fate = OctreeChild::Fate::Empty;
          continue;
        }
        const int depth = n.depth + 1;
        if (!intersect_box(ray, nodes_[c.node].box, ray.tmin, ray.tmax, c.t_enter, c.t_exit)) {
          c.fate = OctreeChild::Fate::Missed;
          log.cull(c.node, depth, Cull::MissedBounds);
        } else if (c.t_enter > closest.t) {
          c.fate = OctreeChild::Fate::BeyondClosestHit;
          log.cull(c.node, depth, Cull::BeyondClosestHit, c.t_enter);
        } else {
          c.fate = OctreeChild::Fate::Pushed;
        }
      }
      log.octree_children(mask, order, 8);
      // Push in reverse, so the first child in visiting order is taken next.
      for (int i = 7; i >= 0; --i) {
        if (order[i].fate != OctreeChild::Fate::Pushed) continue;
        stack[size++] = {order[i].node, order[i].t_enter, order[i].t_exit};
        log.push(order[i].node, n.depth + 1, order[i].t_enter);
      }
    }
    return finish(closest);
  }

 private:
  static constexpr size_t kMaxLeaf = 8;  // subdivide only nodes with more triangles
  static constexpr int kMaxDepth = 20;

  struct Node {
    Box box;
    int depth = 0;
    bool leaf = false;
    uint32_t child[8] = {kNoParent, kNoParent, kNoParent, kNoParent, kNoParent, kNoParent, kNoParent, kNoParent};
    std::vector<uint32_t> prims;  // a leaf's triangles
  };

  static bool overlaps(const Box& a, const Box& b) {
#ifdef PLANT_BUG_OCTREE_BOUNDARY
    return a.lo.x < b.hi.x && a.hi.x > b.lo.x && a.lo.y < b.hi.y && a.hi.y > b.lo.y && a.lo.z < b.hi.z &&
           a.hi.z > b.lo.z;
#else
    // Closed boxes: touching counts.
    return a.lo.x <= b.hi.x && a.hi.x >= b.lo.x && a.lo.y <= b.hi.y && a.hi.y >= b.lo.y && a.lo.z <= b.hi.z &&
           a.hi.z >= b.lo.z;
#endif
  }

  uint32_t build_node(const Box& box, const std::vector<uint32_t>& prims, uint32_t parent, int depth,
                      BuildLog& log) {
    const uint32_t id = uint32_t(nodes_.size());
    nodes_.push_back(Node{});
    nodes_[id].box = box;
    nodes_[id].depth = depth;
    log.node(id, parent, depth, box, prims);
    if (prims.size() <= kMaxLeaf || depth >= kMaxDepth) {
      make_leaf(id, prims, prims.size() <= kMaxLeaf ? LeafWhy::FewTriangles : LeafWhy::MaxDepth, log);
      return id;
    }
    // 8 equal children: octant bit 0 = upper half in x, bit 1 = in y, bit 2 = in z. Along an
    // axis on which the box is flat (a 2D scene) there is only one half: the upper children
    // would be the same as the lower ones.
    const Vec3 c = box.center();
    std::vector<uint32_t> lists[8];
    Box boxes[8];
    bool any_smaller = false;
    for (int o = 0; o < 8; ++o) {
      bool skip = false;
      for (int a = 0; a < 3; ++a) {
        const bool upper = (o >> a) & 1;
        if (upper && !(box.hi[a] > box.lo[a])) skip = true;
        boxes[o].lo[a] = upper ? c[a] : box.lo[a];
        boxes[o].hi[a] = upper ? box.hi[a] : c[a];
      }
      if (skip) continue;
      for (uint32_t p : prims)
        if (overlaps(scene_->box(p), boxes[o])) lists[o].push_back(p);
      if (lists[o].size() < prims.size()) any_smaller = true;
    }
    // No progress: some child would hold every triangle (e.g. identical triangles).
    for (int o = 0; o < 8; ++o)
      if (lists[o].size() == prims.size()) any_smaller = false;
    if (!any_smaller) {
      make_leaf(id, prims, LeafWhy::NoProgress, log);
      return id;
    }
    for (int o = 0; o < 8; ++o) {
      if (lists[o].empty()) continue;  // an empty octant gets no node
      const uint32_t child = build_node(boxes[o], lists[o], id, depth + 1, log);
      nodes_[id].child[o] = child;  // nodes_ may have grown: index, never a reference
    }
    return id;
  }

  void make_leaf(uint32_t id, const std::vector<uint32_t>& prims, LeafWhy why, BuildLog& log) {
    nodes_[id].leaf = true;
    nodes_[id].prims = prims;
    log.leaf(id, prims, why);
  }

  const Scene* scene_ = nullptr;
  std::vector<Node> nodes_;
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(SolutionOctree, SOLUTION_NAME, octree)
