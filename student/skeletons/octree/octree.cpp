// Assignment: the OCTREE of the lecture ("Octree"): cells split into 8 equal sub-cells,
// traversed front to back with the closest-hit test. Fill in build() and intersect() where it
// says TODO; the log calls are already where the lecture's steps happen (keep them there: the
// viewer animates them and `check` reads them). As it stands the root is one empty leaf and
// every ray misses.
//
// Build it into accelviz and check it:
//   scripts/run.sh --student student/skeletons/octree
//   build/bin/accelviz-cli check --structure my_octree
// The kit's reference: student/accelviz_student.h; a complete example: student/example/.
#include <algorithm>
#include <cmath>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class MyOctree : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    scene_ = &scene;
    nodes_.clear();
    // TODO 1: "Start with the bbox of the whole scene": the triangles that are not
    //         degenerate (scene.is_degenerate(p)) and the box around them.
    std::vector<uint32_t> prims;
    const Box box = scene.bounds();
    build_node(box, prims, kNoParent, 0, log);
  }

  Hit intersect(const Ray& ray, TraversalLog log) const override {
    Hit closest;
    closest.t = ray.tmax;  // closest_hit: at first "as far as the ray goes"
    if (nodes_.empty()) return finish(closest);
    // The lecture's OctreeNode::Trace(ray, collision), with a stack instead of recursion.
    // "if ray does not intersect node bounds: return"
    float t_enter = 0.0f, t_exit = 0.0f;
    if (!intersect_box(ray, nodes_[0].box, ray.tmin, ray.tmax, t_enter, t_exit)) {
      log.cull(0, 0, Cull::MissedBounds);
      return finish(closest);
    }
    struct Entry {
      uint32_t node;
      float t_enter, t_exit;
    };
    std::vector<Entry> stack;  // (a fixed array of 8 * (kMaxDepth + 1) entries is faster)
    stack.push_back({0, t_enter, t_exit});
    log.push(0, 0, t_enter);
    // TODO 2: the order of the children, front to back along the ray: the octants i ^ mask
    //         for i = 0..7, where mask has bit a set when the ray runs down axis a.
    const unsigned mask = 0;
    while (!stack.empty()) {
      const Entry e = stack.back();
      stack.pop_back();
      const Node& n = nodes_[e.node];
      log.pop(e.node, n.depth, e.t_enter);
      // TODO 3: "if a collision has already been detected and it's closer than the ray entry
      //         point into this node: return" (skip this node).
      const bool beyond_closest = false;
      if (beyond_closest) {
        log.cull(e.node, n.depth, Cull::BeyondClosestHit, e.t_enter);
        continue;
      }
      log.visit(e.node, n.depth, e.t_enter, e.t_exit);
      if (n.leaf) {
        // "for each polygon in node: if ray intersects polygon: if intersection is closer to
        //  ray origin than collision: update collision" -- test_triangle does all that.
        for (uint32_t p : n.prims) test_triangle(ray, *scene_, p, closest, log);
        continue;
      }
      // "else: for each child_node: child_node.Trace(ray, collision)"
      OctreeChild order[8];  // the children in visiting order, with what became of each
      for (int i = 0; i < 8; ++i) {
        OctreeChild& c = order[i];
        c.octant = int(unsigned(i) ^ mask);
        c.node = n.child[c.octant];
        c.fate = OctreeChild::Fate::Empty;  // no child in this octant
        // TODO 4: for a child that exists: intersect_box(ray, its box, ray.tmin, ray.tmax,
        //         c.t_enter, c.t_exit); a miss -> Fate::Missed and
        //         log.cull(c.node, n.depth + 1, Cull::MissedBounds); entered beyond the
        //         closest hit -> Fate::BeyondClosestHit and log.cull(..., Cull::BeyondClosestHit,
        //         c.t_enter); otherwise Fate::Pushed.
      }
      log.octree_children(mask, order, 8);
      // TODO 5: push the Pushed children so that the FIRST in `order` comes off the stack
      //         first (push them in reverse), each with log.push(c.node, n.depth + 1, c.t_enter).
    }
    return finish(closest);
  }

 private:
  static constexpr size_t kMaxLeaf = 8;  // "Stopping criterion: the number of objects ..."
  static constexpr int kMaxDepth = 16;   // "... and maximal depth"

  struct Node {
    Box box;
    int depth = 0;
    bool leaf = true;
    uint32_t child[8] = {kNoParent, kNoParent, kNoParent, kNoParent,
                         kNoParent, kNoParent, kNoParent, kNoParent};  // by octant; kNoParent: empty
    std::vector<uint32_t> prims;  // a leaf's triangles
  };

  uint32_t build_node(const Box& box, const std::vector<uint32_t>& prims, uint32_t parent, int depth,
                      BuildLog& log) {
    const uint32_t id = uint32_t(nodes_.size());
    nodes_.push_back(Node{});
    nodes_[id].box = box;
    nodes_[id].depth = depth;
    log.node(id, parent, depth, box, prims);
    // TODO 6: "Stopping criterion: the number of objects, and maximal depth": few triangles
    //         or depth >= kMaxDepth -> a leaf (drop the "true ||").
    const bool stop = true || prims.size() <= kMaxLeaf || depth >= kMaxDepth;
    // "Subdivide a cell into 8 equal sub-cells"; octant o: bit 0 = upper half in x, bit 1 = in
    // y, bit 2 = in z.
    Box child_box[8];
    std::vector<uint32_t> child_prims[8];
    for (int o = 0; o < 8 && !stop; ++o) {
      // TODO 7: octant o's eighth of `box`, and every triangle whose box overlaps it (closed:
      //         touching counts, so a triangle in a child's face plane belongs to both sides).
      //         Along an axis on which the box is flat (a 2D scene) there is only one half:
      //         make no upper children there.
      child_box[o] = box;
    }
    // TODO 8: a leaf after all when subdividing cannot help, e.g. when a child got every
    //         triangle (identical or heavily overlapping triangles never separate).
    const bool no_progress = false;
    if (stop || no_progress) {
      nodes_[id].prims = prims;
      const LeafWhy why = no_progress                  ? LeafWhy::NoProgress
                          : prims.size() <= kMaxLeaf ? LeafWhy::FewTriangles
                                                     : LeafWhy::MaxDepth;
      log.leaf(id, prims, why);
      return id;
    }
    nodes_[id].leaf = false;
    for (int o = 0; o < 8; ++o) {
      if (child_prims[o].empty()) continue;  // an empty octant gets no node
      const uint32_t c = build_node(child_box[o], child_prims[o], id, depth + 1, log);
      nodes_[id].child[o] = c;  // nodes_ grew in the recursion: index it, keep no reference
    }
    return id;
  }

  const Scene* scene_ = nullptr;
  std::vector<Node> nodes_;
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(MyOctree, "my_octree", octree)
