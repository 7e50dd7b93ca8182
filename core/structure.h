#pragma once
// The one interface every acceleration structure implements (brute force included), so the
// CLI, the tests, the benchmark and the viewer treat them alike.
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "build_control.h"
#include "build_trace.h"
#include "geometry.h"
#include "params.h"
#include "scene.h"
#include "trace.h"

namespace accel {

/// Statistics of a finished build. Fields that do not apply stay at their defaults
/// (sah_cost NaN, counts 0); `extra` holds structure-specific lines.
struct BuildStats {
  double build_ms = 0.0;              ///< wall time of build()
  double refit_ms = std::nan("");     ///< wall time of the last successful refit() since the build, NaN if none
  size_t memory_bytes = 0;            ///< nodes + primitive references (+ grid cells)
  size_t nodes = 0;                   ///< nodes, or grid cells
  size_t leaves = 0;                  ///< leaves, or grid cells
  size_t empty_leaves = 0;            ///< leaves / cells without a triangle
  int max_depth = 0;                  ///< deepest leaf (root = 0; 0 for a grid)
  size_t prim_references = 0;         ///< triangle references stored in leaves/cells
  size_t prims = 0;                   ///< non-degenerate triangles the structure was built over
  double refs_per_prim() const { return prims ? double(prim_references) / double(prims) : 0.0; }
  size_t max_leaf_size = 0;
  /// leaf_size_histogram[k] = number of leaves holding k triangles, k < size()-1; the last
  /// bucket counts all larger leaves.
  std::vector<size_t> leaf_size_histogram;
  double sah_cost = std::nan("");     ///< expected cost (ct, ci below), normalised to the root's area
  double sah_ct = 0.0, sah_ci = 0.0;  ///< cost constants used for sah_cost
  /// Triangles one leaf test prices as one ci in sah_cost: 1, or 4 for the wide layouts'
  /// four-lane leaf test (a leaf of n triangles costs ci * ceil(n / this)).
  int sah_prims_per_test = 1;
  std::vector<std::pair<std::string, std::string>> extra;  ///< e.g. {"cells", "32x32x16"}

  /// Adds a leaf of `n` triangles to the leaf counters and the histogram.
  void add_leaf(size_t n);
};

/// What the viewer draws of one node or cell (the core knows no GL).
struct NodeView {
  NodeId id = kNoNode;
  int depth = 0;
  bool leaf = false;
  uint32_t prim_count = 0;    ///< triangles referenced by this leaf / cell
  Aabb box;                   ///< node or cell bounds
  BoundingSphere sphere;      ///< sphere-tree nodes only (radius < 0 otherwise)
  int split_axis = -1;        ///< kd-tree inner nodes: axis of the split plane, else -1
  float split_pos = 0.0f;
};

/// Abstract acceleration structure. Build once, then answer closest-hit queries from any
/// number of threads (queries are const).
class Structure {
 public:
  virtual ~Structure() = default;
  /// Registry name, e.g. "bvh".
  virtual std::string name() const = 0;
  /// Builds over `scene` (kept by reference: it must outlive the structure) with validated
  /// parameters, and times it. Errors: an internal limit, or cancelled_error() when
  /// `control` was cancelled (then the structure is left empty: queries miss, no nodes).
  /// `control` (optional) receives the progress, ending at 1.0 on success. Over a 2D scene
  /// (Scene::planar()) the parameters not set explicitly take their 2D defaults
  /// (ParamSpec::planar_default, ParamSet::set_planar).
  Status build(const Scene& scene, const ParamSet& params, BuildControl* control = nullptr);
  /// The same build (the same code, single-threaded) while `recorder` keeps every
  /// construction step (build_trace.h): the structure is exactly the one build() makes.
  /// Timed like build(), but a recorded build is slower: its time is not a benchmark.
  Status build_recorded(const Scene& scene, const ParamSet& params, BuildRecorder& recorder,
                        BuildControl* control = nullptr);
  /// Fits the bounds to the moved vertices of `scene` (Scene::move_vertices) without changing
  /// the topology: the same nodes and primitive lists in the same order, new boxes (O(n)) or
  /// spheres (fitted as the build fits them) -- the fastest "rebuild" when the vertices move
  /// but the triangles do not (an animation). Afterwards queries return exactly the hits of
  /// docs/hits.md on the moved scene, and refitting to unmoved vertices reproduces the
  /// build's bounds -- except after spatial splits (bvh/spheretree builder=sbvh), whose
  /// boxes were clipped to split planes the moved triangles may cross: their refitted boxes
  /// are the triangles' whole boxes (conservative, so still exact hits, at a higher SAH
  /// cost; rebuild to get the clipped boxes back). The tree's quality (SAH cost) may degrade as the vertices travel far
  /// from where it was built: rebuild now and then. `scene` (usually the one built
  /// over, moved in place) replaces the build's scene: it must outlive the structure. Not
  /// concurrently with queries. Timed (BuildStats::refit_ms); deterministic whatever the
  /// thread count. Errors, leaving the structure as it was (stale: rebuild it): a structure
  /// that cannot refit (spatial subdivisions, whose cells depend on the vertices), or a scene
  /// whose valid_prims() are not those built over (a triangle became degenerate or valid).
  Status refit(const Scene& scene);
  /// Closest hit of `ray` (docs/hits.md rule). Fills per-query counters when `stats` is given.
  virtual Hit intersect(const Ray& ray, QueryStats* stats = nullptr) const = 0;
  /// intersect() on each of rays[0..n), into hits[0..n): the same answers, one call for a
  /// batch (a structure may loop where its query is inlined: no virtual call a ray).
  virtual void intersect_batch(const Ray* rays, size_t n, Hit* hits) const {
    for (size_t i = 0; i < n; ++i) hits[i] = intersect(rays[i]);
  }
  /// Same answer as intersect(), recording every traversal step.
  virtual Hit intersect_traced(const Ray& ray, TraceRecorder& recorder) const = 0;
  /// Statistics of the last build, build time included.
  BuildStats build_stats() const;
  /// Calls `fn` for every node (or non-empty grid cell) in id order.
  virtual void for_each_node(const std::function<void(const NodeView&)>& fn) const = 0;
  /// One node or cell, for highlighting a trace step.
  virtual NodeView node_view(NodeId id) const = 0;
  /// The triangles of a leaf or cell (empty for inner nodes).
  virtual std::vector<uint32_t> node_prims(NodeId id) const = 0;
  /// The children of inner node `id` in the structure's own child order (empty for a leaf,
  /// a grid cell or an id out of range): the tree's shape, for the viewer's diagram.
  virtual std::vector<NodeId> node_children(NodeId id) const {
    (void)id;
    return {};
  }

  /// The ray/triangle test used by queries (default watertight).
  void set_kernel(Kernel k) { kernel_ = k; }
  Kernel kernel() const { return kernel_; }

 protected:
  /// The structure's own build, timed by build(). It reports progress to `control` (may be
  /// null), polls its cancel flag at coarse points and, when cancelled, clears itself to
  /// the empty state and returns cancelled_error(). With a `recorder` (build_recorded(),
  /// which runs it in a one-thread arena) its builder runs instantiated for BuildRecorder,
  /// otherwise for NullBuildSink.
  virtual Status build_impl(const Scene& scene, const ParamSet& params, BuildControl* control,
                            BuildRecorder* recorder) = 0;
  /// The structure's own refit, timed by refit(). The default cannot refit: an error naming
  /// the structure.
  virtual Status refit_impl(const Scene& scene);
  /// Everything of BuildStats except build_ms and refit_ms.
  virtual BuildStats compute_stats() const = 0;

  Kernel kernel_ = Kernel::Watertight;

 private:
  Status timed_build(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder);

  double build_ms_ = 0.0;
  double refit_ms_ = std::nan("");
};

/// CRTP glue: turns one `template <TraversalSink Sink> Hit traverse(const Ray&, Sink&) const` in
/// Derived into the virtual query functions, so each traversal is written once.
template <class Derived>
class StructureWithTraversal : public Structure {
 public:
  Hit intersect(const Ray& ray, QueryStats* stats) const override {
    if (stats) {
      StatsSink sink;
      const Hit hit = self().traverse(ray, sink);
      *stats = sink.stats;
      return hit;
    }
    NullSink sink;
    return self().traverse(ray, sink);
  }
  Hit intersect_traced(const Ray& ray, TraceRecorder& recorder) const override {
    return self().traverse(ray, recorder);
  }
  /// The loop where traverse() is known: one virtual call a batch, not one a ray.
  void intersect_batch(const Ray* rays, size_t n, Hit* hits) const override {
    NullSink sink;
    for (size_t i = 0; i < n; ++i) hits[i] = self().traverse(rays[i], sink);
  }

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

/// Takes the outcome of testing triangle `prim` into `closest` (whose t is the current
/// tmax). The first hit in [tmin, tmax] counts even at t == tmax (inclusive); later ones
/// only when strictly closer, so ties keep the first triangle found. A triangle that is
/// already the closest hit never replaces itself: structures that hold a triangle in several
/// leaves or cells (kd-tree, grid, octree, bvh builder=sbvh) may test it again, and near tmax
/// the test's double-precision fallback could return a t an ulp or so below its first one.
template <TraversalSink Sink>
ACCEL_FORCE_INLINE bool take_triangle_result(uint32_t prim, bool hit, const TriangleHit& th, Hit& closest,
                                             Sink& sink) {
  sink.test_prim(prim, hit, th.t);
  if (hit && (closest.prim < 0 || (th.t < closest.t && closest.prim != int32_t(prim)))) {
    closest = Hit{int32_t(prim), th.t, th.u, th.v};
    sink.new_closest(prim, th.t);
    return true;
  }
  return false;
}

/// Tests triangle `prim` with vertices (p0, p1, p2) and takes the result into `closest`.
template <TraversalSink Sink>
ACCEL_FORCE_INLINE bool test_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, uint32_t prim,
                                      const TriangleTester& tester, Hit& closest, Sink& sink) {
  TriangleHit th{kInf, 0.0f, 0.0f};
  const bool hit = tester.intersect(p0, p1, p2, closest.t, &th);
  return take_triangle_result(prim, hit, th, closest, sink);
}

/// The same, reading the triangle's vertices from the scene.
template <TraversalSink Sink>
inline bool test_triangle(const Scene& scene, const TriangleTester& tester, uint32_t prim, Hit& closest,
                          Sink& sink) {
  return test_triangle(scene.vertex(prim, 0), scene.vertex(prim, 1), scene.vertex(prim, 2), prim, tester, closest,
                       sink);
}

/// Initial "closest hit" of a query: no triangle, t = ray.tmax.
inline Hit no_hit(const Ray& ray) {
  Hit h;
  h.t = ray.tmax;
  return h;
}
/// Turns the running closest hit into the query's answer (t = inf on a miss).
inline Hit finish_hit(Hit h) {
  if (!h.valid()) h = Hit{};
  return h;
}
/// Ends a query: the answer of finish_hit(), reported to the sink.
template <TraversalSink Sink>
inline Hit finish_query(const Hit& closest, Sink& sink) {
  const Hit result = finish_hit(closest);
  sink.done(result);
  return result;
}

/// A 64-bit FNV-1a digest of what the structure's views show: every node in id order (its
/// id, depth, kind, box and sphere bits, split plane, children) and every leaf's triangles in
/// their stored order. Equal digests mean the same structure for all that can be seen of it;
/// `accelviz-cli stats --digest` prints it, to check that a faster build makes the same tree.
uint64_t structure_digest(const Structure& structure);

}  // namespace accel
