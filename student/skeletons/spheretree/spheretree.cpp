// Assignment: the SPHERE TREE of the lecture ("BVH (AABB-Tree, Sphere-Tree)"): a bounding
// volume hierarchy whose volumes are spheres, built top down by a median split, traversed
// nearest sphere first. Fill in build() and intersect() where it says TODO; the log calls
// are already where the lecture's steps happen (keep them there: the viewer animates them
// and `check` reads them). As it stands the root is one empty leaf and every ray misses.
//
// Build it into accelviz and check it:
//   scripts/run.sh --student student/skeletons/spheretree
//   build/bin/accelviz-cli check --structure my_spheretree
// The kit's reference: student/accelviz_student.h; a complete example: student/example/.
//
// The lecture's traversal, dist(node) being where the ray enters the node's sphere (a stack
// that takes the nearer child first works as well):
//   Pqueue q <- init with root;  closest_hit = inf
//   while q not empty:
//     node <- extract front from q                  // = nearest BV
//     if dist(node) <= closest_hit:                  // else: skip this subtree
//       if node is leaf: intersect ray with all polygons in node, update closest_hit
//       else: forall children of node: if ray intersects child: insert child in q with its distance
// Warning: the closest ray-BV intersection and the closest ray-primitive intersection can
// occur in different BVs -- never stop at the first leaf that hits.
#include <algorithm>
#include <cmath>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class MySphereTree : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    scene_ = &scene;
    nodes_.clear();
    prims_.clear();
    // TODO 1: "Construct elementary BVs around all objects": the triangles that are not
    //         degenerate (scene.is_degenerate(p)) into prims_; scene.box(p) is each one's box.
    build_node(0, prims_.size(), kNoParent, 0, log);
  }

  Hit intersect(const Ray& ray, TraversalLog log) const override {
    Hit closest;
    closest.t = ray.tmax;  // closest_hit: at first "as far as the ray goes"
    if (nodes_.empty()) return finish(closest);
    float t_enter = 0.0f, t_exit = 0.0f;
    if (!intersect_sphere(ray, nodes_[0].sphere, ray.tmin, closest.t, t_enter, t_exit)) {
      log.cull(0, 0, Cull::MissedBounds);
      return finish(closest);
    }
    struct Entry {  // a node waiting in the queue, with its distance
      uint32_t node;
      float t_enter, t_exit;
    };
    std::vector<Entry> queue = {{0, t_enter, t_exit}};
    log.push(0, 0, t_enter);
    while (!queue.empty()) {
      // TODO 2: "node <- extract front from q": the NEAREST entry (a priority queue, e.g.
      //         std::priority_queue), or the top of a stack onto which the farther child was
      //         pushed first. (back() as it stands takes the most recent: plain DFS.)
      const Entry e = queue.back();
      queue.pop_back();
      const Node& n = nodes_[e.node];
      log.pop(e.node, n.depth, e.t_enter);
      // TODO 3: "if dist(node) <= closest_hit, else: skip this subtree"
      const bool beyond_closest = false;
      if (beyond_closest) {
        log.cull(e.node, n.depth, Cull::BeyondClosestHit, e.t_enter);
        continue;
      }
      log.visit(e.node, n.depth, e.t_enter, e.t_exit);
      if (n.leaf) {
        // "intersect ray with all polygons in node, update closest_hit, if any polygon is closer"
        for (uint32_t i = n.first; i < n.first + n.count; ++i) test_triangle(ray, *scene_, prims_[i], closest, log);
        continue;
      }
      // "forall children of node: if ray intersects child: insert child in q with its distance"
      for (uint32_t child : {n.left, n.right}) {
        float c_enter = 0.0f, c_exit = 0.0f;
        // TODO 4: does the ray meet the child's sphere before closest_hit? intersect_sphere(ray,
        //         nodes_[child].sphere, ray.tmin, closest.t, c_enter, c_exit)
        const bool hit = false;
        if (!hit) {
          log.cull(child, n.depth + 1, Cull::MissedBounds);
          continue;
        }
        queue.push_back({child, c_enter, c_exit});
        log.push(child, n.depth + 1, c_enter);
      }
    }
    return finish(closest);
  }

 private:
  static constexpr int kMaxLeaf = 4;    // "Terminate, when a node contains less than n objects"
  static constexpr int kMaxDepth = 48;  // a safety net

  struct Node {
    Sphere sphere;  // radius < 0: none yet (every ray misses it)
    bool leaf = true;
    uint32_t first = 0, count = 0;  // a leaf's triangles: prims_[first, first + count)
    uint32_t left = 0, right = 0;   // an inner node's children
    int depth = 0;
  };

  uint32_t build_node(size_t begin, size_t end, uint32_t parent, int depth, BuildLog& log) {
    const uint32_t id = uint32_t(nodes_.size());
    nodes_.push_back(Node{});
    nodes_[id].depth = depth;
    const size_t n = end - begin;
    // TODO 5: the node's box (around the boxes of prims_[begin, end)) and its bounding
    //         sphere, which must CONTAIN every vertex of its triangles: e.g. centre = the
    //         box's centre, radius = the largest distance from it to a vertex (a touch larger
    //         for rounding). scene_->triangle(p).v0, .v1, .v2 are the vertices.
    Box box;
    log.node(id, parent, depth, box, prims_.data() + begin, n);
    log.sphere(id, nodes_[id].sphere);
    // TODO 6: a leaf when n <= kMaxLeaf, or depth >= kMaxDepth (drop the "true ||").
    if (true || n <= size_t(kMaxLeaf) || depth >= kMaxDepth) {
      nodes_[id].first = uint32_t(begin);
      nodes_[id].count = uint32_t(n);
      log.leaf(id, prims_.data() + begin, n, n <= size_t(kMaxLeaf) ? LeafWhy::FewTriangles : LeafWhy::MaxDepth);
      return id;
    }
    // TODO 7: "2. Sort all objects according to their center along the axis (e.g. the longest
    //         extent of the centres), 3. partition the scene along the median; assign half of
    //         the objects to the left and the right subtree": std::nth_element on
    //         prims_[begin, end) by scene_->centroid(p)[axis] puts the median at `mid`.
    const int axis = 0;
    const size_t mid = begin + n / 2;
    const float position = 0.0f;  // the median's centre along the axis
    const float cost = 0.0f;      // C(B) of this split (for the viewer), against the leaf's n
    log.split(id, axis, position, cost, float(n), uint32_t(mid - begin), uint32_t(end - mid));
    // "4. Repeat 1-3 recursively"
    const uint32_t l = build_node(begin, mid, id, depth + 1, log);
    const uint32_t r = build_node(mid, end, id, depth + 1, log);
    Node& node = nodes_[id];  // only now: nodes_ grew in the recursion (references go stale)
    node.leaf = false, node.left = l, node.right = r;
    return id;
  }

  const Scene* scene_ = nullptr;
  std::vector<Node> nodes_;
  std::vector<uint32_t> prims_;  // the triangles, reordered so that each leaf's are together
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(MySphereTree, "my_spheretree", spheretree)
