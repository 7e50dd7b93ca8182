// Lecturer's test solution: the kit's worked example (student/example/median_bvh.cpp), an
// AABB tree split at the median and traversed with a stack, nearer child first -- copied
// unchanged but for its registered name and the planted bug below.
//
// Planted bug (off by default), compiled as a variant by the kit's tests:
//   PLANT_BUG_BVH_FIRST_HIT  the traversal returns as soon as a leaf produced a hit (the
//                            first leaf hit, not the closest: the lecture's warning).
//   PLANT_BUG_BVH_FALSE_CULL a popped node is culled as "beyond the closest hit" when its exit
//                            (not its entry) lies beyond it.
//   PLANT_BUG_BVH_SLAB_NAN   a hand-written slab test: (lo - o) * (1/d) is NaN for d = -0 with
//                            the origin on the box's plane, and the box counts as missed.
#include <algorithm>
#include <cmath>
#include <vector>

#include "accelviz_student.h"

#ifndef SOLUTION_NAME
#define SOLUTION_NAME "sol_bvh"
#endif

using namespace accelviz;

namespace {

class MedianBvh : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    scene_ = &scene;
    nodes_.clear();
    prims_.clear();
    // Zero-area triangles are never hit: leave them out.
    for (uint32_t p = 0; p < scene.size(); ++p)
      if (!scene.is_degenerate(p)) prims_.push_back(p);
    if (prims_.empty()) return;  // an empty tree: every ray misses
    build_node(0, prims_.size(), kNoParent, 0, log);
  }

  Hit intersect(const Ray& ray, TraversalLog log) const override {
    Hit closest;
    closest.t = ray.tmax;  // the lecture's closest_hit, at first "as far as the ray goes"
    if (nodes_.empty()) return finish(closest);
    float t_enter, t_exit;
    if (!intersect_box(ray, nodes_[0].box, ray.tmin, closest.t, t_enter, t_exit)) {
      log.cull(0, 0, Cull::MissedBounds);
      return finish(closest);
    }
    struct Entry {
      uint32_t node;
      float t_enter, t_exit;
    };
    Entry stack[kMaxDepth + 2];  // ordered depth-first: at most one pending child per level
    int size = 0;
    stack[size++] = {0, t_enter, t_exit};
    log.push(0, 0, t_enter);
    while (size > 0) {
      const Entry e = stack[--size];
      const Node& n = nodes_[e.node];
      log.pop(e.node, n.depth, e.t_enter);
      // A node pushed before a closer hit was found may now start beyond it.
#ifdef PLANT_BUG_BVH_FALSE_CULL
      if (e.t_exit > closest.t) {
#else
      if (e.t_enter > closest.t) {
#endif
        log.cull(e.node, n.depth, Cull::BeyondClosestHit, e.t_enter);
        continue;
      }
      log.visit(e.node, n.depth, e.t_enter, e.t_exit);
      if (n.count > 0) {  // a leaf: test its triangles, keep the closest hit
        for (uint32_t i = n.first; i < n.first + n.count; ++i) test_triangle(ray, *scene_, prims_[i], closest, log);
#ifdef PLANT_BUG_BVH_FIRST_HIT
        if (closest.valid()) return finish(closest);  // "found a hit: done" -- wrong
#endif
        continue;
      }
      // Inner node: test both children's boxes, push the farther first so the nearer is
      // taken next. Never stop at the first hit: a farther box may still hold a nearer
      // triangle (the lecture's trap).
      Entry hit[2];
      int hits = 0;
      for (uint32_t child : {n.left, n.right}) {
        float c_enter, c_exit;
        if (box_test(ray, nodes_[child].box, ray.tmin, closest.t, c_enter, c_exit))
          hit[hits++] = {child, c_enter, c_exit};
        else
          log.cull(child, n.depth + 1, Cull::MissedBounds);
      }
      if (hits == 2 && hit[1].t_enter > hit[0].t_enter) std::swap(hit[0], hit[1]);
      for (int i = 0; i < hits; ++i) {
        stack[size++] = hit[i];
        log.push(hit[i].node, n.depth + 1, hit[i].t_enter);
      }
    }
    return finish(closest);
  }

 private:
  static bool box_test(const Ray& ray, const Box& box, float t_min, float t_max, float& t_enter, float& t_exit) {
#ifdef PLANT_BUG_BVH_SLAB_NAN
    for (int a = 0; a < 3; ++a) {  // the textbook slab test, without a guard for 0 * inf
      float t0 = (box.lo[a] - ray.origin[a]) * ray.inv_direction[a];
      float t1 = (box.hi[a] - ray.origin[a]) * ray.inv_direction[a];
      if (t0 > t1) std::swap(t0, t1);
      t_min = t0 > t_min ? t0 : t_min;
      t_max = t1 < t_max ? t1 : t_max;
    }
    t_enter = t_min, t_exit = t_max;
    return t_min <= t_max;
#else
    return intersect_box(ray, box, t_min, t_max, t_enter, t_exit);
#endif
  }

  static constexpr int kMaxLeaf = 4;    // triangles per leaf
  static constexpr int kMaxDepth = 48;  // a safety net: median splits halve, so ~log2(n)

  struct Node {
    Box box;
    uint32_t first = 0, count = 0;  // a leaf's triangles: prims_[first, first + count)
    uint32_t left = 0, right = 0;   // an inner node's children
    int depth = 0;
  };

  Box bounds_of(size_t begin, size_t end) const {
    Box b;
    for (size_t i = begin; i < end; ++i) b.grow(scene_->box(prims_[i]));
    return b;
  }

  uint32_t build_node(size_t begin, size_t end, uint32_t parent, int depth, BuildLog& log) {
    const uint32_t id = uint32_t(nodes_.size());
    nodes_.push_back(Node{});
    const Box box = bounds_of(begin, end);
    nodes_[id].box = box;
    nodes_[id].depth = depth;
    const size_t n = end - begin;
    log.node(id, parent, depth, box, &prims_[begin], n);
    if (n <= size_t(kMaxLeaf) || depth >= kMaxDepth) {
      nodes_[id].first = uint32_t(begin);
      nodes_[id].count = uint32_t(n);
      log.leaf(id, &prims_[begin], n, n <= size_t(kMaxLeaf) ? LeafWhy::FewTriangles : LeafWhy::MaxDepth);
      return id;
    }
    // The lecture's median split: along the longest axis of the centroids' box, half the
    // triangles on each side (ties broken by index, so the tree is the same every run).
    Box centroids;
    for (size_t i = begin; i < end; ++i) centroids.grow(scene_->centroid(prims_[i]));
    const int axis = centroids.longest_axis();
    const size_t mid = begin + n / 2;
    std::nth_element(prims_.begin() + long(begin), prims_.begin() + long(mid), prims_.begin() + long(end),
                     [&](uint32_t a, uint32_t b) {
                       const float ca = scene_->centroid(a)[axis], cb = scene_->centroid(b)[axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    // The SAH cost of this split against the leaf's, for the viewer (the median ignores it).
    const float area = std::max(box.area(), 1e-30f);
    const float cost = 1.0f + (bounds_of(begin, mid).area() * float(mid - begin) +
                               bounds_of(mid, end).area() * float(end - mid)) / area;
    log.split(id, axis, scene_->centroid(prims_[mid])[axis], cost, float(n), uint32_t(mid - begin),
              uint32_t(end - mid));
    const uint32_t left = build_node(begin, mid, id, depth + 1, log);
    const uint32_t right = build_node(mid, end, id, depth + 1, log);
    nodes_[id].left = left;  // nodes_ may have grown: index, never a reference held across
    nodes_[id].right = right;
    return id;
  }

  const Scene* scene_ = nullptr;
  std::vector<Node> nodes_;
  std::vector<uint32_t> prims_;
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(MedianBvh, SOLUTION_NAME, bvh)
