// Lecturer's test solution: the sphere tree of the lecture ("BVH (AABB-Tree, Sphere-Tree)"),
// written the way a student would: the median split of the kit's worked example, with a
// bounding sphere per node (centre = the centre of its triangles' box, radius = the largest
// distance to a vertex of its triangles), traversed with a stack, nearer child first.
//
// Planted bug (off by default), compiled as a variant by the kit's tests:
//   PLANT_BUG_SPHERE_TOO_SMALL  the radius is computed from the triangles' centroids instead
//                               of their vertices: the sphere does not contain its triangles.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "accelviz_student.h"

#ifndef SOLUTION_NAME
#define SOLUTION_NAME "sol_spheretree"
#endif

using namespace accelviz;

namespace {

class SolutionSphereTree : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    scene_ = &scene;
    nodes_.clear();
    prims_.clear();
    for (uint32_t p = 0; p < scene.size(); ++p)
      if (!scene.is_degenerate(p)) prims_.push_back(p);  // zero-area: never hit
    if (prims_.empty()) return;                           // an empty tree: every ray misses
    build_node(0, prims_.size(), kNoParent, 0, log);
  }

  Hit intersect(const Ray& ray, TraversalLog log) const override {
    Hit closest;
    closest.t = ray.tmax;
    if (nodes_.empty()) return finish(closest);
    float t_enter, t_exit;
    if (!intersect_sphere(ray, nodes_[0].sphere, ray.tmin, closest.t, t_enter, t_exit)) {
      log.cull(0, 0, Cull::MissedBounds);
      return finish(closest);
    }
    struct Entry {
      uint32_t node;
      float t_enter, t_exit;
    };
    Entry stack[kMaxDepth + 2];  // depth-first: at most one pending child per level
    int size = 0;
    stack[size++] = {0, t_enter, t_exit};
    log.push(0, 0, t_enter);
    while (size > 0) {
      const Entry e = stack[--size];
      const Node& n = nodes_[e.node];
      log.pop(e.node, n.depth, e.t_enter);
      if (e.t_enter > closest.t) {  // pushed before a closer hit was found
        log.cull(e.node, n.depth, Cull::BeyondClosestHit, e.t_enter);
        continue;
      }
      log.visit(e.node, n.depth, e.t_enter, e.t_exit);
      if (n.count > 0) {  // a leaf: test its triangles, keep the closest hit
        for (uint32_t i = n.first; i < n.first + n.count; ++i) test_triangle(ray, *scene_, prims_[i], closest, log);
        continue;
      }
      // Inner node: test both children's spheres, push the farther first.
      Entry hit[2];
      int hits = 0;
      for (uint32_t child : {n.left, n.right}) {
        float c_enter, c_exit;
        if (intersect_sphere(ray, nodes_[child].sphere, ray.tmin, closest.t, c_enter, c_exit))
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
  static constexpr int kMaxLeaf = 4;
  static constexpr int kMaxDepth = 48;

  struct Node {
    Sphere sphere;
    uint32_t first = 0, count = 0;  // a leaf's triangles: prims_[first, first + count)
    uint32_t left = 0, right = 0;   // an inner node's children
    int depth = 0;
  };

  Box bounds_of(size_t begin, size_t end) const {
    Box b;
    for (size_t i = begin; i < end; ++i) b.grow(scene_->box(prims_[i]));
    return b;
  }

  /// A sphere around triangles prims_[begin, end): centre at their box's centre, radius the
  /// largest distance to one of their vertices, enlarged a little for rounding.
  Sphere sphere_of(size_t begin, size_t end) const {
    Sphere s;
    s.center = bounds_of(begin, end).center();
    float r = 0.0f;
    for (size_t i = begin; i < end; ++i) {
      const Triangle& t = scene_->triangle(prims_[i]);
#ifdef PLANT_BUG_SPHERE_TOO_SMALL
      r = std::max(r, length(t.centroid() - s.center));
#else
      for (const Vec3& v : {t.v0, t.v1, t.v2}) r = std::max(r, length(v - s.center));
#endif
    }
    s.radius = r * (1.0f + 1e-6f);
    return s;
  }

  uint32_t build_node(size_t begin, size_t end, uint32_t parent, int depth, BuildLog& log) {
    const uint32_t id = uint32_t(nodes_.size());
    nodes_.push_back(Node{});
    const Box box = bounds_of(begin, end);
    nodes_[id].sphere = sphere_of(begin, end);
    nodes_[id].depth = depth;
    const size_t n = end - begin;
    log.node(id, parent, depth, box, &prims_[begin], n);
    log.sphere(id, nodes_[id].sphere);
    if (n <= size_t(kMaxLeaf) || depth >= kMaxDepth) {
      nodes_[id].first = uint32_t(begin);
      nodes_[id].count = uint32_t(n);
      log.leaf(id, &prims_[begin], n, n <= size_t(kMaxLeaf) ? LeafWhy::FewTriangles : LeafWhy::MaxDepth);
      return id;
    }
    // The median split: along the longest axis of the centroids' box, half the triangles on
    // each side (ties broken by index, so the tree is the same every run).
    Box centroids;
    for (size_t i = begin; i < end; ++i) centroids.grow(scene_->centroid(prims_[i]));
    const int axis = centroids.longest_axis();
    const size_t mid = begin + n / 2;
    std::nth_element(prims_.begin() + long(begin), prims_.begin() + long(mid), prims_.begin() + long(end),
                     [&](uint32_t a, uint32_t b) {
                       const float ca = scene_->centroid(a)[axis], cb = scene_->centroid(b)[axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    // The cost of this split against the leaf's, for the viewer: the children's sphere
    // surface areas relative to this node's (the median ignores it).
    const float r2 = std::max(nodes_[id].sphere.radius * nodes_[id].sphere.radius, 1e-30f);
    const float rl = sphere_of(begin, mid).radius, rr = sphere_of(mid, end).radius;
    const float cost = 1.0f + (rl * rl * float(mid - begin) + rr * rr * float(end - mid)) / r2;
    log.split(id, axis, scene_->centroid(prims_[mid])[axis], cost, float(n), uint32_t(mid - begin),
              uint32_t(end - mid));
    const uint32_t left = build_node(begin, mid, id, depth + 1, log);
    const uint32_t right = build_node(mid, end, id, depth + 1, log);
    nodes_[id].left = left;  // nodes_ may have grown: index, never a reference
    nodes_[id].right = right;
    return id;
  }

  const Scene* scene_ = nullptr;
  std::vector<Node> nodes_;
  std::vector<uint32_t> prims_;
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(SolutionSphereTree, SOLUTION_NAME, spheretree)
