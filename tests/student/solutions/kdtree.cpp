// Lecturer's test solution: the kd-tree of the lecture ("kD-Tree"), written the way a student
// would: each node's region split in the middle of the cell or at the median of the triangles,
// on the axis and at the position the cost function rates lowest (and not at all when the
// leaf is cheaper), triangles touching or straddling the plane going to both children; the
// traversal is the lecture's traverse(r, n, t_min, t_max) with its three cases, made
// iterative with a stack of the deferred far children, and the early exit "if t_hit < t_split
// return".
//
// Planted bugs (off by default), compiled as variants by the kit's tests:
//   PLANT_BUG_KD_NO_CASE_C        case (c) is missing: "t_split outside [t_min, t_max]" is
//                                 treated as case (b), so only the near child is visited.
//   PLANT_BUG_KD_NO_TSPLIT_CHECK  a hit found in the near child ends the traversal even when
//                                 it lies beyond t_split.
//   PLANT_BUG_KD_SLIDE_NEAR       the slide as written: near = the child holding the origin, and
//                                 case (c) whenever t_split < t_min -- wrong when the plane lies
//                                 behind the origin (t_split < 0).
//   PLANT_BUG_KD_MINUS_ZERO       t_split = (split - o) * (1/d) for every ray and near chosen by
//                                 d >= 0: a direction component of -0 (1/d = -inf) goes astray.
//   PLANT_BUG_KD_C_AS_A           case (c) is missing and falls through to case (a): right
//                                 answers, but the near child is visited where the ray is not.
//   PLANT_BUG_KD_FALSE_EARLY_EXIT the early exit compares t_hit with the far child's t_max
//                                 instead of its t_split.
//   PLANT_BUG_KD_NO_PROGRESS      no "little progress" rule: overlapping triangles are copied
//                                 into both children again and again (a runaway allocation).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "accelviz_student.h"

#ifndef SOLUTION_NAME
#define SOLUTION_NAME "sol_kdtree"
#endif

using namespace accelviz;

namespace {

class SolutionKdTree : public StudentStructure {
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
    root_box_ = box;
    // pbrt's depth rule: 8 + 1.3 log2(N), at most kMaxDepth.
    max_depth_ = std::min(kMaxDepth, int(std::lround(8.0 + 1.3 * std::log2(double(prims.size())))));
    build_node(box, prims, kNoParent, 0, log);
  }

  Hit intersect(const Ray& ray, TraversalLog log) const override {
    Hit closest;
    closest.t = ray.tmax;
    if (nodes_.empty()) return finish(closest);
    // Intersect the ray with the root box -> [t_min, t_max].
    float t_min, t_max;
    if (!intersect_box(ray, root_box_, ray.tmin, ray.tmax, t_min, t_max)) {
      log.cull(0, 0, Cull::MissedBounds);
      return finish(closest);
    }
    struct Entry {
      uint32_t node;
      int depth;
      float t_min, t_max;
    };
    Entry stack[kMaxDepth + 1];  // one deferred far child per level of the current path
    int size = 0;
    uint32_t id = 0;
    int depth = 0;
    for (;;) {
      const Node& n = nodes_[id];
      log.visit(id, depth, t_min, t_max);
      if (!n.leaf) {
        const int axis = n.axis;
        // t_split = signed distance along r to the splitting plane. A ray parallel to the
        // plane never crosses it (+inf), unless it lies in it (NaN: both children, below).
#if defined(PLANT_BUG_KD_SLIDE_NEAR) || defined(PLANT_BUG_KD_MINUS_ZERO)
        const float t_split = (n.split - ray.origin[axis]) * ray.inv_direction[axis];
#else
        const float t_split = ray.direction[axis] == 0.0f && ray.origin[axis] != n.split
                                  ? kInfinity
                                  : (n.split - ray.origin[axis]) * ray.inv_direction[axis];
#endif
        // near = the child the ray is in before t_split (for a ray starting before the plane
        // the child containing its origin): the lower one when it runs up the axis.
#if defined(PLANT_BUG_KD_SLIDE_NEAR)
        const bool lower_first = ray.origin[axis] <= n.split;  // "the child containing the origin"
#elif defined(PLANT_BUG_KD_MINUS_ZERO)
        const bool lower_first = ray.direction[axis] >= 0.0f;  // true for -0 too
#else
        const bool lower_first = ray.direction[axis] > 0.0f ||
                                 (ray.direction[axis] == 0.0f && ray.origin[axis] <= n.split);
#endif
        const uint32_t near = lower_first ? n.left : n.right;
        const uint32_t far = lower_first ? n.right : n.left;
        log.kd_split(t_min, t_split, t_max, near, far, axis);
        ++depth;
        // t_split carries a few roundings: cases (b) and (c) only when the plane is clearly
        // outside [t_min, t_max]; near the ends both children are visited (harmless).
#if defined(PLANT_BUG_KD_SLIDE_NEAR) || defined(PLANT_BUG_KD_MINUS_ZERO)
        if (t_split > t_max) {  // (b), compared as the slide writes it
#elif defined(PLANT_BUG_KD_NO_CASE_C)
        if (below(t_max, t_split) || below(t_split, t_min)) {  // (b) ... and (c) mistaken for it
#else
        if (below(t_max, t_split)) {  // (b) the plane lies beyond t_max: near only
#endif
          log.cull(far, depth, Cull::MissedBounds, t_split);
          id = near;
          continue;
        }
#if defined(PLANT_BUG_KD_SLIDE_NEAR) || defined(PLANT_BUG_KD_MINUS_ZERO)
        const bool case_c = t_split < t_min;  // compared as the slide writes it
#elif defined(PLANT_BUG_KD_C_AS_A)
        const bool case_c = false;  // forgotten: falls through to case (a)
#else
        const bool case_c = below(t_split, t_min);
#endif
        if (case_c) {  // (c) the plane lies before t_min: far only
          log.cull(near, depth, Cull::MissedBounds, t_split);
          id = far;
          continue;
        }
        // (a) near on [t_min, t_split] now, far on [t_split, t_max] later. A NaN t_split (the
        // ray lies in the plane) gives both children the whole interval.
        const float far_min = t_split > t_min ? t_split : t_min;
        stack[size++] = {far, depth, far_min, t_max};
        log.push(far, depth, far_min);
        if (t_split < t_max) t_max = t_split;
        id = near;
        continue;
      }
      // A leaf: test every triangle, keep the closest hit (it may lie beyond this leaf).
      for (uint32_t p : n.prims) test_triangle(ray, *scene_, p, closest, log);
      // Take the next deferred far child, unless the hit found lies before its t_split:
      // the lecture's early exit "if t_hit < t_split: return t_hit". A hit beyond t_split
      // must not end the search: the far child may hold a nearer triangle.
      bool more = false;
      while (size > 0) {
        const Entry e = stack[--size];
        log.pop(e.node, e.depth, e.t_min);
#if defined(PLANT_BUG_KD_NO_TSPLIT_CHECK)
        const bool exits = closest.valid();
#elif defined(PLANT_BUG_KD_FALSE_EARLY_EXIT)
        const bool exits = closest.valid() && below(closest.t, e.t_max);
#else
        const bool exits = closest.valid() && below(closest.t, e.t_min);
#endif
        log.kd_far_pop(closest.t, e.t_min, e.node, exits);
        if (exits) {
          log.cull(e.node, e.depth, Cull::BeyondClosestHit, e.t_min);
          continue;
        }
        id = e.node;
        depth = e.depth;
        t_min = e.t_min;
        t_max = e.t_max;
        more = true;
        break;
      }
      if (!more) break;
    }
    return finish(closest);
  }

 private:
  static constexpr size_t kMaxLeaf = 4;  // a node with at most this many triangles is a leaf
  static constexpr int kMaxDepth = 40;

  struct Node {
    bool leaf = false;
    int axis = 0;
    float split = 0.0f;
    uint32_t left = 0, right = 0;
    std::vector<uint32_t> prims;  // a leaf's triangles
  };

  /// a < b by more than rounding (a relative 1e-6): t values computed in float.
  static bool below(float a, float b) { return a < b - 1e-6f * std::max(std::fabs(a), std::fabs(b)); }

  uint32_t build_node(const Box& region, const std::vector<uint32_t>& prims, uint32_t parent, int depth,
                      BuildLog& log) {
    const uint32_t id = uint32_t(nodes_.size());
    nodes_.push_back(Node{});
    log.node(id, parent, depth, region, prims);
    if (prims.size() <= kMaxLeaf || depth >= max_depth_) {
      make_leaf(id, prims, prims.size() <= kMaxLeaf ? LeafWhy::FewTriangles : LeafWhy::MaxDepth, log);
      return id;
    }
    // Split plane: on each of the 3 axes the lecture's two naive positions, the middle of the
    // cell and the median of the geometry (the triangles' centres); the one the cost function
    // rates lowest wins. C(B) = C_t + C_i (A_L / A n_L + A_R / A n_R), C_t = C_i = 1.
    int axis = 0;
    float split = 0.0f, cost = kInfinity;
    for (int a = 0; a < 3; ++a) {
      std::vector<float> centres;
      for (uint32_t p : prims) centres.push_back(scene_->centroid(p)[a]);
      std::nth_element(centres.begin(), centres.begin() + long(centres.size() / 2), centres.end());
      for (const float candidate : {region.center()[a], centres[centres.size() / 2]}) {
        if (!(candidate > region.lo[a] && candidate < region.hi[a])) continue;  // cuts nothing
        const float c = split_cost(region, prims, a, candidate);
        if (c < cost) cost = c, axis = a, split = candidate;
      }
    }
    const float leaf_cost = float(prims.size());
    if (cost >= leaf_cost) {  // no split pays (or the region is too thin to cut)
      make_leaf(id, prims, LeafWhy::NoGain, log);
      return id;
    }
    // Distribute: a triangle whose box touches or straddles the plane goes to both sides.
    std::vector<uint32_t> left, right;
    for (uint32_t p : prims) {
      const Box& b = scene_->box(p);
      if (b.lo[axis] <= split) left.push_back(p);
      if (b.hi[axis] >= split) right.push_back(p);
    }
    // Little progress: most triangles would go to both children (identical or heavily
    // overlapping triangles never separate; splitting them again and again only copies them,
    // and in a flat scene the cost function alone would allow it).
#ifdef PLANT_BUG_KD_NO_PROGRESS
    if (false) {
#else
    if (4 * (left.size() + right.size()) > 7 * prims.size()) {
#endif
      make_leaf(id, prims, LeafWhy::NoProgress, log);
      return id;
    }
    Box left_region = region, right_region = region;
    left_region.hi[axis] = split;
    right_region.lo[axis] = split;
    log.split(id, axis, split, cost, leaf_cost, uint32_t(left.size()), uint32_t(right.size()));
    nodes_[id].axis = axis;
    nodes_[id].split = split;
    const uint32_t l = build_node(left_region, left, id, depth + 1, log);
    const uint32_t r = build_node(right_region, right, id, depth + 1, log);
    nodes_[id].left = l;  // nodes_ may have grown: index, never a reference
    nodes_[id].right = r;
    return id;
  }

  /// C(B) of the plane at `position` along `axis`: the triangles touching or straddling it
  /// count on both sides.
  float split_cost(const Box& region, const std::vector<uint32_t>& prims, int axis, float position) const {
    size_t n_left = 0, n_right = 0;
    for (uint32_t p : prims) {
      if (scene_->box(p).lo[axis] <= position) ++n_left;
      if (scene_->box(p).hi[axis] >= position) ++n_right;
    }
    Box left = region, right = region;
    left.hi[axis] = position;
    right.lo[axis] = position;
    const float area = std::max(region.area(), 1e-30f);
    return 1.0f + (left.area() * float(n_left) + right.area() * float(n_right)) / area;
  }

  void make_leaf(uint32_t id, const std::vector<uint32_t>& prims, LeafWhy why, BuildLog& log) {
    nodes_[id].leaf = true;
    nodes_[id].prims = prims;
    log.leaf(id, prims, why);
  }

  const Scene* scene_ = nullptr;
  Box root_box_;
  int max_depth_ = kMaxDepth;
  std::vector<Node> nodes_;
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(SolutionKdTree, SOLUTION_NAME, kdtree)
