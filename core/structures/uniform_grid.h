#pragma once
// Uniform grid: the scene box cut into NX x NY x NZ cells of equal size, each cell listing
// the triangles that touch it; rays walk the cells they pierce with the 3D-DDA of
// Amanatides & Woo 1987, "A Fast Voxel Traversal Algorithm for Ray Tracing".
//
// Robustness (why the traversal never misses a triangle):
//  - Triangles are inserted into every cell their box, grown by a pad of 2^-28 times the
//    grid's largest coordinate, touches (and, with insert=exact, whose equally grown box
//    the triangle overlaps). A triangle touching a cell boundary is therefore in both cells.
//  - The DDA runs in double precision with crossing distances computed from the boundary
//    index (never accumulated), so the t interval of a cell is where the (float) ray really
//    is in that cell up to ~2^-52 of the distance travelled: far below the pad for any
//    origin closer than ~2^20 scene sizes. The box clip uses the padded box, so rays
//    grazing the scene box at a face or an edge still enter it.
//  - The walk only stops once the closest hit lies within the cell just processed
//    (t_hit <= t_exit): a hit found beyond the cell is kept and later cells are still walked,
//    since a closer triangle may sit in the next cell.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <vector>

#include "build_control.h"
#include "structure.h"

namespace accel {

inline constexpr int kGridMaxRes = 1024;                  ///< cells per axis, at most
/// The most cells a grid has (256 MB of offsets) whatever the memory budget: past it a
/// rule's resolution is shrunk, so a rule of thumb never makes a grid slow to walk.
inline constexpr size_t kGridMaxCells = size_t(1) << 26;

/// How the grid resolution is chosen when `res` is not given.
enum class GridResolutionRule : uint8_t {
  Cbrt,     ///< lambda * cbrt(N) cells per axis of a cube (lambda^3 * N cells in all), cuboid-like cells
  AvgSize,  ///< cell edge = average triangle size (mean bbox extent) / lambda
};

/// How triangles are assigned to cells.
enum class GridInsertion : uint8_t {
  Bbox,   ///< every cell the triangle's bounding box touches (the lecture's choice)
  Exact,  ///< only cells the triangle itself overlaps (Akenine-Moller 2001 separating axes)
};

/// Build settings of a grid, decoded from the structure's parameters.
struct GridConfig {
  GridResolutionRule rule = GridResolutionRule::Cbrt;
  double lambda = 2.0;                 ///< per-axis factor of the rule (see GridResolutionRule)
  bool explicit_res = false;           ///< use `res` instead of the rule
  std::array<int, 3> res{16, 16, 16};  ///< cells per axis when explicit_res
  GridInsertion insertion = GridInsertion::Exact;
  /// Most triangle references (tests lower it). A rule's resolution shrinks to fit it and
  /// the memory limit; an explicit res over either is an error.
  size_t max_references = size_t(1) << 28;
  /// The build's memory budget in bytes (memory_budget.h): the cells, the references and
  /// the build's per-triangle scratch must fit it.
  size_t memory_limit = SIZE_MAX;
};

/// The built grid: plain data in compressed-sparse-row form.
struct GridData {
  Aabb bounds;                       ///< box of the valid triangles (empty: no triangles)
  std::array<int, 3> res{1, 1, 1};   ///< cells per axis, each in [1, kGridMaxRes]
  DVec3 cell_size{0.0};              ///< extent / res per axis (0 on a flat axis)
  double pad = 0.0;                  ///< insertion pad (world units), see the file comment
  bool clamped_to_budget = false;    ///< the rule's resolution was shrunk to the cell/reference budget
  /// cell_start[c] = index in prim_ids of the first triangle of cell c; cell c holds
  /// prim_ids[cell_start[c] .. cell_start[c+1]). Size cells+1. Cell id c = x + NX*(y + NY*z).
  std::vector<uint32_t> cell_start;
  std::vector<uint32_t> prim_ids;    ///< triangle indices, grouped by cell, ascending per cell
  size_t cell_count() const { return size_t(res[0]) * size_t(res[1]) * size_t(res[2]); }
};
static_assert(sizeof(decltype(GridData::cell_start)::value_type) == 4 &&
                  sizeof(decltype(GridData::prim_ids)::value_type) == 4,
              "a cell costs 4 bytes (one CSR offset), a triangle reference 4 more");

/// A resolution and whether the rule's answer had to be shrunk to the cell budget.
struct GridResolution {
  std::array<int, 3> res{1, 1, 1};
  bool clamped_to_budget = false;
};

/// Cells per axis for `config` over the valid triangles of `scene` (box `bounds`), each axis
/// clamped to [1, kGridMaxRes]; a flat axis (zero extent) gets 1 cell. A rule's resolution
/// over kGridMaxCells is shrunk uniformly to fit (it is a rule of thumb); an explicit `res`
/// over the budget is an error naming the parameter.
Result<GridResolution> grid_resolution(const Scene& scene, const Aabb& bounds, const GridConfig& config);

/// Builds the grid over `scene.valid_prims()`. Errors (naming the parameter) when an
/// explicit res exceeds a memory budget, or cancelled_error() when `control` is cancelled.
/// Progress: 0.1 once the resolution fits the budget, then triangles inserted / N in each
/// of the two insertion passes (counting to 0.55, filling to 1.0), from the calling thread;
/// cancel is polled per batch of triangles. Both passes run on TBB's threads (the caller's
/// task_arena); the grid is the same for any thread count.
/// With a `recorder`, every construction step is recorded (build_trace.h), the insertion
/// serially; the grid is the same. Steps: scene_box (the valid triangles' box); grid_resolution
/// (the grid box, values = {lambda, N, volume, cube root}, NaN where the rule has no such
/// number, see resolution_terms() in the .cpp; the final cells per axis); for every valid
/// triangle in index order grid_insert (its box's cell range [lo, hi] and the linear ids
/// x + NX*(y + NY*z), ascending, of the cells it is stored in: the whole range with
/// insert=bbox, the cells the exact test accepts with insert=exact); done (cell count).
Result<GridData> build_grid(const Scene& scene, const GridConfig& config, BuildControl* control = nullptr,
                            BuildRecorder* recorder = nullptr);

/// Conservative triangle/box overlap (Akenine-Moller 2001, "Fast 3D Triangle-Box Overlap
/// Testing", 13 separating axes), in double, the box grown by `pad`: true whenever the
/// triangle touches the closed box, possibly also for a triangle within ~pad of it.
bool triangle_box_overlap(const DVec3& box_min, const DVec3& box_max, const Vec3& p0, const Vec3& p1,
                          const Vec3& p2, double pad);

/// Everything the grid's parameters set: the build and the traversal's mailboxing.
struct UniformGridOptions {
  GridConfig build;
  bool mailbox = true;
};

/// Uniform grid with 3D-DDA traversal (Amanatides & Woo 1987) and optional mailboxing.
class UniformGrid final : public StructureWithTraversal<UniformGrid> {
 public:
  /// resolution, lambda, res, insert, mailbox: the one declaration of the grid's parameters.
  static const ParamTable<UniformGridOptions>& param_table();
  static std::vector<ParamSpec> param_specs() { return param_table().specs(); }
  std::string name() const override { return "grid"; }
  /// Every non-empty cell in id order: depth 0, leaf, its box and triangle count.
  void for_each_node(const std::function<void(const NodeView&)>& fn) const override;
  /// Any cell id (empty cells too); an out-of-range id gives a default view with that id.
  NodeView node_view(NodeId id) const override;
  /// The cell's triangles (empty for an empty or out-of-range cell).
  std::vector<uint32_t> node_prims(NodeId id) const override;
  const GridData& data() const { return grid_; }
  bool mailbox() const { return mailbox_; }

  /// The one traversal: clip the ray to the grid box, then 3D-DDA through the cells
  /// (Amanatides & Woo 1987). Calls sink.enter_cell for every cell stepped into (empty
  /// ones too), test_prim/new_closest inside test_triangle (not for prims skipped by the
  /// mailbox), and done at the end.
  template <TraversalSink Sink>
  Hit traverse(const Ray& ray, Sink& sink) const {
    const TriangleTester tester(ray, kernel_);
    Hit closest = no_hit(ray);
    if (!grid_.prim_ids.empty()) {
      if (mailbox_)
        walk<true>(ray, tester, closest, sink);
      else
        walk<false>(ray, tester, closest, sink);
    }
    return finish_query(closest, sink);
  }

 protected:
  Status build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) override;
  BuildStats compute_stats() const override { return stats_; }

 private:
  /// Mailboxing (Arnaldi, Priol & Bouatouch 1987; used by Amanatides & Woo 1987) per ray:
  /// a small direct-mapped table of the prim ids this ray tested, on the stack, so queries
  /// stay const and thread-safe with no allocation. A prim evicted by a colliding id is
  /// merely tested again (same answer: the kernel's result does not depend on the cell).
  static constexpr uint32_t kMailboxSize = 32;  // power of two
  /// The 3D-DDA walk of one ray (defined below), with or without the mailbox.
  template <bool kMailbox, TraversalSink Sink>
  void walk(const Ray& ray, const TriangleTester& tester, Hit& closest, Sink& sink) const;
  Aabb cell_box(NodeId id) const;

  const Scene* scene_ = nullptr;
  GridData grid_;
  bool mailbox_ = false;
  DVec3 lo_{0.0}, hi_{0.0};  // grid box grown by the pad: the box rays are clipped to
  BuildStats stats_;
};

// ---------------------------------------------------------------------------------------
// The 3D-DDA (Amanatides & Woo 1987), following the lecture's loop: step the axis whose
// next boundary crossing is nearest, until the ray leaves the grid or the closest hit lies
// in the cell just processed.
template <bool kMailbox, TraversalSink Sink>
void UniformGrid::walk(const Ray& ray, const TriangleTester& tester, Hit& closest, Sink& sink) const {
  const double org[3] = {ray.org.x, ray.org.y, ray.org.z};
  const double dir[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
  // Clip [tmin, tmax] to the (padded) grid box with the slab test. A zero component (+0 or
  // -0) never restricts t: the origin is inside that slab or the ray misses; this avoids
  // the 0 * inf = NaN of the reciprocal form.
  double t0 = ray.tmin, t1 = ray.tmax;
  double inv[3];
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) {
      if (org[a] < lo_[a] || org[a] > hi_[a]) return;
      inv[a] = 0.0;
      continue;
    }
    inv[a] = 1.0 / dir[a];
    double ta = (lo_[a] - org[a]) * inv[a], tb = (hi_[a] - org[a]) * inv[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return;

  // Starting cell: the cell of the entry point, clamped (the entry point may lie in the pad
  // or, by rounding, a hair outside the box).
  int idx[3], step[3], out[3];
  double t_next[3], t_base[3], t_delta[3];
  int64_t cell = 0;
  const int64_t stride[3] = {1, grid_.res[0], int64_t(grid_.res[0]) * grid_.res[1]};
  for (int a = 0; a < 3; ++a) {
    const int n = grid_.res[a];
    int i = 0;
    if (n > 1) {
      const double p = dir[a] == 0.0 ? org[a] : org[a] + t0 * dir[a];
      const double f = std::floor((p - double(grid_.bounds.min[a])) / grid_.cell_size[a]);
      i = f > 0.0 ? (f < double(n - 1) ? int(f) : n - 1) : 0;  // NaN -> 0
    }
    idx[a] = i;
    cell += int64_t(i) * stride[a];
    if (n == 1 || dir[a] == 0.0) {
      // Never step on this axis: a single slab (the ray leaves through t1) or no motion.
      step[a] = 0;
      out[a] = -2;
      t_next[a] = std::numeric_limits<double>::infinity();
      t_base[a] = t_delta[a] = 0.0;
      continue;
    }
    step[a] = dir[a] > 0.0 ? 1 : -1;
    out[a] = dir[a] > 0.0 ? n : -1;
    // Crossing of boundary plane k (coordinate min + k*cell): t = t_base + k * t_delta.
    // Computed from k each step rather than accumulated, so 1024 steps add no error.
    t_base[a] = (double(grid_.bounds.min[a]) - org[a]) * inv[a];
    t_delta[a] = grid_.cell_size[a] * inv[a];
    t_next[a] = t_base[a] + double(step[a] > 0 ? i + 1 : i) * t_delta[a];
  }

  [[maybe_unused]] uint32_t mailbox[kMailbox ? kMailboxSize : 1];
  if constexpr (kMailbox) std::fill(std::begin(mailbox), std::end(mailbox), ~uint32_t(0));

  const uint32_t* starts = grid_.cell_start.data();
  const uint32_t* prims = grid_.prim_ids.data();
  double t_enter = t0;
  for (;;) {
    const int axis = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
    const double t_exit = std::min(t_next[axis], t1);
    // The first cell's exit may precede t0 when the entry point rounded into it from a
    // neighbour: report an empty interval rather than a reversed one.
    sink.enter_cell(NodeId(cell), float(t_enter), float(std::max(t_exit, t_enter)));
    if constexpr (Sink::kRecords) {  // the lecture's X, Y, Z, stepX.., tMaxX.., tDeltaX..
      GridDdaVars v;
      for (int a = 0; a < 3; ++a) {
        v.cell[a] = idx[a];
        v.step[a] = step[a];
        v.t_max[a] = float(t_next[a]);
        v.t_delta[a] = float(std::abs(t_delta[a]));
      }
      v.next_axis = axis;
      v.dims = scene_->planar() ? 2 : 3;
      sink.vars(v);
    }
    for (uint32_t k = starts[cell], end = starts[cell + 1]; k < end; ++k) {
      const uint32_t prim = prims[k];
      if constexpr (kMailbox) {
        uint32_t& slot = mailbox[prim & (kMailboxSize - 1)];
        if (slot == prim) continue;
        slot = prim;
      }
      test_triangle(*scene_, tester, prim, closest, sink);
    }
    // Stop once the closest hit (or tmax) lies within this cell: nothing in a later cell
    // can be closer. closest.t is ray.tmax while nothing was hit.
    if (t_exit >= std::min(t1, double(closest.t))) return;
    idx[axis] += step[axis];
    if (idx[axis] == out[axis]) return;  // left the grid
    cell += step[axis] * stride[axis];
    t_enter = std::max(t_enter, t_next[axis]);  // monotonic even after a rounded start cell
    t_next[axis] = t_base[axis] + double(step[axis] > 0 ? idx[axis] + 1 : idx[axis]) * t_delta[axis];
  }
}

}  // namespace accel
