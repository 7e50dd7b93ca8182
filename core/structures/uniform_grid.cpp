#include "structures/uniform_grid.h"

#include <cstdio>
#include <functional>
#include <string>

#include "parallel.h"

namespace accel {
namespace {

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string res_text(const std::array<int, 3>& r) {
  return std::to_string(r[0]) + "x" + std::to_string(r[1]) + "x" + std::to_string(r[2]);
}

/// The parameter an over-budget error should name: `res` when given, else the rule's lambda.
std::string driving_param_text(const GridConfig& c) {
  if (c.explicit_res)
    return "grid parameter 'res' = " + std::to_string(c.res[0]) + "," + std::to_string(c.res[1]) + "," +
           std::to_string(c.res[2]);
  return "grid parameter 'lambda' = " + format_number(c.lambda) +
         (c.rule == GridResolutionRule::Cbrt ? " (resolution=cbrt)" : " (resolution=avgsize)");
}

/// The lecture's rule "resolution = lambda * cbrt(N)" per axis of a cube, generalised to
/// any box with cuboid-like cells (Cleary & Wyvill 1988; Wald et al. 2006 write it as
/// n_axis = extent_axis * cbrt(density * N / volume), density = lambda^3): choose the cell
/// edge s so that the box holds lambda^3 * N cubic cells. Axes shorter than one cell
/// (flat or thin scenes) get a single cell and the others share the cell budget, so a flat
/// scene gets lambda^3 * N square cells rather than one huge row. A 2D scene (`dims` 2) takes
/// the rule's 2D form, lambda * sqrt(N) cells per axis of a square: lambda^2 * N cells.
/// Returns real-valued cells per axis (rounded by fit_resolution).
/// The cbrt rule's iteration: the cell edge s, the axes it gives more than one cell, and the
/// volume s was computed from (the product of those axes' extents; NaN for an empty box).
struct CbrtRule {
  double s = 0.0;
  double volume = std::numeric_limits<double>::quiet_NaN();
  bool active[3] = {false, false, false};
};
CbrtRule cbrt_rule(const DVec3& extent, size_t n_prims, double lambda, int dims) {
  const double target = std::pow(lambda, dims) * double(n_prims);
  CbrtRule r;
  for (int a = 0; a < 3; ++a) r.active[a] = extent[a] > 0.0;
  for (int iter = 0; iter < 3; ++iter) {
    int k = 0;
    double product = 1.0;
    for (int a = 0; a < 3; ++a)
      if (r.active[a]) ++k, product *= extent[a];
    if (k == 0) break;
    r.volume = product;
    r.s = std::pow(product / std::max(target, 1e-300), 1.0 / k);
    bool changed = false;
    for (int a = 0; a < 3; ++a)
      if (r.active[a] && extent[a] < r.s) r.active[a] = false, changed = true;
    if (!changed) break;
  }
  return r;
}

DVec3 resolution_cbrt(const DVec3& extent, size_t n_prims, double lambda, int dims) {
  const CbrtRule r = cbrt_rule(extent, n_prims, lambda, dims);
  DVec3 n(1.0);
  for (int a = 0; a < 3; ++a)
    if (r.active[a] && r.s > 0.0) n[a] = extent[a] / r.s;
  return n;
}

/// The lecture's other rule of thumb: cell edge about the average triangle size, measured
/// by its bounding box (the mean of the box's three extents), divided by lambda.
DVec3 resolution_avgsize(const Scene& scene, const DVec3& extent, double lambda) {
  double sum = 0.0;
  for (uint32_t prim : scene.valid_prims()) {
    const Vec3 e = scene.triangle_bounds(prim).extent();
    sum += (double(e.x) + double(e.y) + double(e.z)) / 3.0;
  }
  const size_t count = scene.valid_prims().size();
  const double s = count ? sum / double(count) / lambda : 0.0;
  DVec3 n(1.0);
  for (int a = 0; a < 3; ++a)
    if (extent[a] > 0.0 && s > 0.0) n[a] = extent[a] / s;
  return n;
}

/// Rounds a rule's real-valued resolution to whole cells in [1, kGridMaxRes] per axis and at
/// most `max_cells` in all. Over either limit every axis shrinks by the same factor, so the
/// cells keep the shape the rule gave them.
GridResolution fit_resolution(DVec3 n, size_t max_cells) {
  GridResolution out;
  n = glm::max(n, DVec3(1.0));
  double f = std::min(1.0, double(kGridMaxRes) / std::max({n.x, n.y, n.z}));
  const double wanted = n.x * n.y * n.z * f * f * f;
  if (wanted > double(max_cells)) f *= std::cbrt(double(max_cells) / wanted);
  out.clamped_to_budget = f < 1.0;
  for (int a = 0; a < 3; ++a) out.res[a] = std::clamp(int(std::lround(std::max(1.0, n[a] * f))), 1, kGridMaxRes);
  // Rounding up may overshoot the budget by a little: take whole cells off the largest axis.
  while (size_t(out.res[0]) * size_t(out.res[1]) * size_t(out.res[2]) > max_cells) {
    int& largest = *std::max_element(out.res.begin(), out.res.end());
    largest = std::max(1, largest - 1);
  }
  return out;
}

/// Index of the cell holding coordinate x on `axis`, clamped to the grid.
int cell_index(const GridData& g, int axis, double x) {
  const int n = g.res[axis];
  if (n == 1) return 0;
  const double f = std::floor((x - double(g.bounds.min[axis])) / g.cell_size[axis]);
  return f > 0.0 ? (f < double(n - 1) ? int(f) : n - 1) : 0;
}

/// Closed box of cell (i, j, k) in double; the last cell ends exactly at the grid's max.
void cell_bounds(const GridData& g, const int idx[3], DVec3* lo, DVec3* hi) {
  for (int a = 0; a < 3; ++a) {
    (*lo)[a] = double(g.bounds.min[a]) + double(idx[a]) * g.cell_size[a];
    (*hi)[a] = idx[a] + 1 == g.res[a] ? double(g.bounds.max[a])
                                      : double(g.bounds.min[a]) + double(idx[a] + 1) * g.cell_size[a];
  }
}

/// Range of cells [lo, hi] (per axis) touched by the prim's box grown by the pad.
void prim_cell_range(const GridData& g, const Aabb& b, int lo[3], int hi[3]) {
  for (int a = 0; a < 3; ++a) {
    lo[a] = cell_index(g, a, double(b.min[a]) - g.pad);
    hi[a] = cell_index(g, a, double(b.max[a]) + g.pad);
  }
}

/// A triangle's cell range, computed once and kept for both insertion passes (the index
/// needs a division per bound). Cell indices are below kGridMaxRes, so 16 bits hold them.
struct CellRange {
  uint16_t lo[3], hi[3];
  uint64_t cells() const {
    return uint64_t(hi[0] - lo[0] + 1) * uint64_t(hi[1] - lo[1] + 1) * uint64_t(hi[2] - lo[2] + 1);
  }
};
static_assert(kGridMaxRes <= 65536, "cell indices fit CellRange's 16 bits");

CellRange cell_range(const GridData& g, const Aabb& b) {
  int lo[3], hi[3];
  prim_cell_range(g, b, lo, hi);
  CellRange r;
  for (int a = 0; a < 3; ++a) r.lo[a] = uint16_t(lo[a]), r.hi[a] = uint16_t(hi[a]);
  return r;
}

/// insert=bbox: every cell of the prim's (padded) box range.
template <class Fn>
void insert_bbox(const GridData& g, const CellRange& range, Fn&& fn) {
  for (int z = range.lo[2]; z <= range.hi[2]; ++z)
    for (int y = range.lo[1]; y <= range.hi[1]; ++y)
      for (int x = range.lo[0]; x <= range.hi[0]; ++x)
        fn(size_t(x) + size_t(g.res[0]) * (size_t(y) + size_t(g.res[1]) * size_t(z)));
}

/// insert=exact: the cells of the box range that the triangle itself overlaps
/// (Akenine-Moller 2001), tested against the cell grown by the pad so no cell is lost.
/// `memo` holds one bit per candidate cell of the range (in the loop's order): the counting
/// pass (memo_valid = false) sets them, the filling pass (true) reads them, no test again.
template <class Fn>
void insert_exact(const GridData& g, const Scene& scene, uint32_t prim, const CellRange& range, uint64_t* memo,
                  bool memo_valid, Fn&& fn) {
  const int lo[3] = {range.lo[0], range.lo[1], range.lo[2]}, hi[3] = {range.hi[0], range.hi[1], range.hi[2]};
  // A triangle whose box range is a single cell, or a single row of cells, overlaps every
  // cell of it: it is connected and spans the row, and the row's other two extents hold
  // it whole. Only ranges two or three cells wide need the test.
  if ((lo[0] != hi[0]) + (lo[1] != hi[1]) + (lo[2] != hi[2]) <= 1) return insert_bbox(g, range, fn);
  const size_t nx = size_t(g.res[0]), ny = size_t(g.res[1]);
  size_t k = 0;
  if (memo_valid) {
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x, ++k)
          if ((memo[k >> 6] >> (k & 63)) & 1u) fn(size_t(x) + nx * (size_t(y) + ny * size_t(z)));
    return;
  }
  const Vec3 &p0 = scene.vertex(prim, 0), &p1 = scene.vertex(prim, 1), &p2 = scene.vertex(prim, 2);
  // The cells holding a vertex need no test either: the vertex is in the cell (up to the
  // rounding of the index, ~2^-52 of the coordinates, far inside the pad), and the test
  // projects all three vertices on every axis, so it always answers true there.
  int vertex_cell[3][3];
  const Vec3* verts[3] = {&p0, &p1, &p2};
  for (int v = 0; v < 3; ++v)
    for (int a = 0; a < 3; ++a) vertex_cell[v][a] = cell_index(g, a, double((*verts[v])[a]));
  const auto holds_vertex = [&](int x, int y, int z) {
    for (const auto& vc : vertex_cell)
      if (vc[0] == x && vc[1] == y && vc[2] == z) return true;
    return false;
  };
  for (size_t w = 0, words = (range.cells() + 63) / 64; w < words; ++w) memo[w] = 0;
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x, ++k) {
        bool overlap = holds_vertex(x, y, z);
        if (!overlap) {
          const int idx[3] = {x, y, z};
          DVec3 cmin, cmax;
          cell_bounds(g, idx, &cmin, &cmax);
          overlap = triangle_box_overlap(cmin, cmax, p0, p1, p2, g.pad);
        }
        if (overlap) {
          memo[k >> 6] |= uint64_t(1) << (k & 63);
          fn(size_t(x) + nx * (size_t(y) + ny * size_t(z)));
        }
      }
}

/// Runs fn(k) for k in [0, n) in parallel, in batches: a cancel is seen within one batch,
/// and the check costs nothing next to a batch's insertions. Progress (done / n) goes to
/// `span`, counted by all threads. Returns false when cancelled.
template <class Fn>
bool for_each_prim_batch(size_t n, ProgressSpan& span, Fn&& fn) {
  constexpr size_t kBatch = 4096;
  ProgressCounter done(&span, n);
  par::parallel_for(
      par::blocked_range<size_t>(0, n, kBatch),
      [&](const par::blocked_range<size_t>& r) {
        if (done.stopped()) return;
        for (size_t k = r.begin(); k < r.end(); ++k) fn(k);
        done.add(r.size());
      },
      par::simple_partitioner());  // batches of at most kBatch, also on one thread
  return !done.stopped();
}

/// True when the projections of the triangle (vertices v relative to the box centre) and
/// of the box (half extents h) onto `axis` are disjoint. All three vertices are projected,
/// so the test is a valid separating-axis test even for an axis rounded off its ideal
/// direction; the pad inside h absorbs the rounding of the projections.
bool separated(const DVec3& axis, const DVec3 v[3], const DVec3& h) {
  const double p0 = glm::dot(axis, v[0]), p1 = glm::dot(axis, v[1]), p2 = glm::dot(axis, v[2]);
  const double r = h.x * std::abs(axis.x) + h.y * std::abs(axis.y) + h.z * std::abs(axis.z);
  return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

}  // namespace

bool triangle_box_overlap(const DVec3& box_min, const DVec3& box_max, const Vec3& p0, const Vec3& p1,
                          const Vec3& p2, double pad) {
  // Akenine-Moller 2001: the triangle and the box are disjoint iff one of 13 axes separates
  // them: the 3 box normals, the triangle normal, and the 9 cross products of box and
  // triangle edges. Done in double about the box centre, box grown by pad.
  const DVec3 c = 0.5 * (box_min + box_max);
  const DVec3 h = 0.5 * (box_max - box_min) + DVec3(pad);
  const DVec3 v[3] = {DVec3(p0) - c, DVec3(p1) - c, DVec3(p2) - c};
  // 1. Box normals: projections are the coordinates themselves.
  for (int a = 0; a < 3; ++a)
    if (std::min({v[0][a], v[1][a], v[2][a]}) > h[a] || std::max({v[0][a], v[1][a], v[2][a]}) < -h[a]) return false;
  // 2. The triangle's plane.
  const DVec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  if (separated(glm::cross(e[0], e[1]), v, h)) return false;
  // 3. The 9 axes unit_a x edge, written out: for unit x the axis is (0, -e.z, e.y), and
  // separated() would compute 0*v.x - e.z*v.y + e.y*v.z and h.x*0 + h.y*|e.z| + h.z*|e.y|;
  // dropping the zero terms (x + 0 = x exactly) leaves the same doubles, hence the same
  // answers, with a third of the work.
  const auto apart = [](double q0, double q1, double q2, double r) {
    return std::min({q0, q1, q2}) > r || std::max({q0, q1, q2}) < -r;
  };
  for (const DVec3& f : e) {
    if (apart(-f.z * v[0].y + f.y * v[0].z, -f.z * v[1].y + f.y * v[1].z, -f.z * v[2].y + f.y * v[2].z,
              h.y * std::abs(f.z) + h.z * std::abs(f.y)))
      return false;
    if (apart(f.z * v[0].x + -f.x * v[0].z, f.z * v[1].x + -f.x * v[1].z, f.z * v[2].x + -f.x * v[2].z,
              h.x * std::abs(f.z) + h.z * std::abs(f.x)))
      return false;
    if (apart(-f.y * v[0].x + f.x * v[0].y, -f.y * v[1].x + f.x * v[1].y, -f.y * v[2].x + f.x * v[2].y,
              h.x * std::abs(f.y) + h.y * std::abs(f.x)))
      return false;
  }
  return true;
}

namespace {

/// Bytes a grid of `cells` cells with `references` triangle references needs while it is
/// built: the offsets and the references it keeps, and per triangle its cell range and, for
/// insert=exact, the memo of overlap answers (one bit per candidate cell).
double grid_build_bytes(const GridConfig& config, size_t triangles, double cells, double references) {
  double bytes = 4.0 * (cells + 1.0) + 4.0 * references + double(triangles) * sizeof(CellRange);
  if (config.insertion == GridInsertion::Exact) bytes += double(triangles + 1) * sizeof(size_t) + references / 8.0;
  return bytes;
}

/// The most cells the budget leaves room for next to the triangles' scratch (cells take at
/// most half of it: the references need the rest).
size_t max_cells_in_budget(const GridConfig& config, size_t triangles) {
  const double scratch = grid_build_bytes(config, triangles, 0.0, 0.0);
  const double room = (double(config.memory_limit) - scratch) / 2.0 / 4.0;
  return size_t(std::clamp(room, 1.0, double(kGridMaxCells)));
}

}  // namespace

Result<GridResolution> grid_resolution(const Scene& scene, const Aabb& bounds, const GridConfig& config) {
  const DVec3 extent = DVec3(bounds.extent());
  const size_t triangles = scene.valid_prims().size();
  if (config.explicit_res) {
    GridResolution out;
    for (int a = 0; a < 3; ++a) out.res[a] = std::clamp(config.res[a], 1, kGridMaxRes);
    const size_t cells = size_t(out.res[0]) * size_t(out.res[1]) * size_t(out.res[2]);
    if (cells > kGridMaxCells)
      return make_error(driving_param_text(config) + ": would create " + res_text(out.res) + " = " +
                        std::to_string(cells) + " cells (limit " + std::to_string(kGridMaxCells) + "); lower it");
    const double bytes = grid_build_bytes(config, triangles, double(cells), 0.0);
    if (bytes > double(config.memory_limit))
      return make_error(driving_param_text(config) + ": " + res_text(out.res) + " cells " +
                        over_budget_text(bytes, config.memory_limit) + "; lower it");
    return out;
  }
  // A rule of thumb (avgsize on a teapot in a stadium, or a large lambda) may ask for more
  // than the budget: it is shrunk to fit rather than refused.
  const size_t max_cells = max_cells_in_budget(config, triangles);
  if (config.rule == GridResolutionRule::AvgSize)
    return fit_resolution(resolution_avgsize(scene, extent, config.lambda), max_cells);
  return fit_resolution(resolution_cbrt(extent, triangles, config.lambda, scene.planar() ? 2 : 3), max_cells);
}

namespace {

/// The numbers of the GridResolution step (build_trace.h: values = {lambda, N, volume, cube
/// root}), NaN where one does not apply:
///  * cbrt: lambda; N = valid triangles; volume = the product of the extents of the axes the
///    rule gives more than one cell (the box volume, or the area of a flat scene); cube root =
///    (lambda^3 * N / volume)^(1/k) over those k axes (lambda^2 in a 2D scene), the rule's
///    cells per unit length:
///    extent * it = the real-valued cells of an axis before rounding (on a unit cube it is
///    the lecture's lambda * cbrt(N)).
///  * avgsize: lambda and N; volume and cube root NaN (the rule has neither).
///  * explicit res: N; lambda, volume and cube root NaN.
/// The cells per axis of the event are the grid's final ones (after any shrinking to the
/// memory budget).
std::array<double, 4> resolution_terms(const GridConfig& config, const DVec3& extent, size_t n_prims, int dims) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::array<double, 4> v = {config.lambda, double(n_prims), nan, nan};
  if (config.explicit_res) {
    v[0] = nan;
    return v;
  }
  if (config.rule != GridResolutionRule::Cbrt) return v;
  // The numbers of the very iteration resolution_cbrt() runs.
  const CbrtRule r = cbrt_rule(extent, n_prims, config.lambda, dims);
  v[2] = r.volume;
  v[3] = r.s > 0.0 ? 1.0 / r.s : nan;
  return v;
}

/// The resolution the parameters ask for over the box g.bounds (shrunk to the memory budget
/// where a rule asks for too much), and the pad of the exact test: 2^-28 of the largest
/// coordinate, far above the rounding of the cell bounds.
Status set_resolution(GridData& g, const Scene& scene, const GridConfig& config) {
  auto res = grid_resolution(scene, g.bounds, config);
  if (!res) return res.error();
  g.res = res.value().res;
  g.clamped_to_budget = res.value().clamped_to_budget;
  const double m = std::max({std::abs(double(g.bounds.min.x)), std::abs(double(g.bounds.min.y)),
                             std::abs(double(g.bounds.min.z)), std::abs(double(g.bounds.max.x)),
                             std::abs(double(g.bounds.max.y)), std::abs(double(g.bounds.max.z))});
  g.pad = std::ldexp(m, -28);
  return {};
}

/// Each valid triangle's cell range at g's resolution (into `ranges`); returns their cells
/// summed: the candidates of the insertion.
uint64_t compute_cell_ranges(const GridData& g, const Scene& scene, std::vector<CellRange>& ranges) {
  const std::vector<uint32_t>& valid = scene.valid_prims();
  ranges.resize(valid.size());
  return par::parallel_reduce(
      par::blocked_range<size_t>(0, valid.size(), 16384), uint64_t(0),
      [&](const par::blocked_range<size_t>& r, uint64_t sum) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
          ranges[k] = cell_range(g, scene.triangle_bounds(valid[k]));
          sum += ranges[k].cells();
        }
        return sum;
      },
      std::plus<>());
}

/// Why a grid that cannot shrink (an explicit res, or one cell) is refused: its references
/// over the limit, or its `bytes` over the memory budget.
Error references_error(const GridData& g, const GridConfig& config, size_t triangles, uint64_t candidates,
                       double bytes, bool over_memory) {
  const std::string refs = "would create " + std::to_string(candidates) + " triangle references in " +
                           res_text(g.res) + " cells";
  if (over_memory && !config.explicit_res)  // one cell: the scene alone is over the budget
    return make_error("grid: " + std::to_string(triangles) + " triangles in one cell " +
                      over_budget_text(bytes, config.memory_limit) + "; raise the memory limit");
  if (over_memory)
    return make_error(driving_param_text(config) + ": " + refs + " and " +
                      over_budget_text(bytes, config.memory_limit) + "; lower it");
  return make_error(driving_param_text(config) + ": " + refs + " (limit " + std::to_string(config.max_references) +
                    "); lower it");
}

/// Shrinks a rule's resolution towards what the reference limit and the memory budget leave
/// room for. References shrink at least as fast as the cell count's cube root: one or two
/// rounds. The memory's share of references is what the budget leaves after the cells.
void shrink_resolution(GridData& g, const GridConfig& config, size_t triangles, uint64_t candidates) {
  const double room = (double(config.memory_limit) - grid_build_bytes(config, triangles, double(g.cell_count()), 0.0)) /
                      (config.insertion == GridInsertion::Exact ? 4.125 : 4.0);
  const double fit = std::max(1.0, std::min(double(config.max_references), room));
  const double f = std::min(0.9, std::cbrt(fit / double(candidates)));
  for (int& n : g.res) n = std::max(1, int(double(n) * f));
  g.clamped_to_budget = true;
}

/// Bounds the work and memory before doing it: the box ranges give an upper bound on the
/// references of either insertion (and on the overlap tests of insert=exact). A rule's
/// resolution shrinks until it fits; an explicit res is refused. Sets g.cell_size; returns
/// the triangles' cell ranges at the final resolution.
Result<std::vector<CellRange>> fit_references(GridData& g, const Scene& scene, const GridConfig& config) {
  const size_t triangles = scene.valid_prims().size();
  const DVec3 extent = DVec3(g.bounds.extent());
  std::vector<CellRange> ranges;
  for (;;) {
    for (int a = 0; a < 3; ++a) g.cell_size[a] = extent[a] / double(g.res[a]);
    const uint64_t candidates = compute_cell_ranges(g, scene, ranges);
    const double bytes = grid_build_bytes(config, triangles, double(g.cell_count()), double(candidates));
    const bool over_memory = bytes > double(config.memory_limit);
    if (candidates <= config.max_references && !over_memory) return ranges;
    if (config.explicit_res || g.cell_count() == 1)
      return references_error(g, config, triangles, candidates, bytes, over_memory);
    shrink_resolution(g, config, triangles, candidates);
  }
}

/// Puts triangles into cells by the chosen insertion, and counts (bump) or fills the cells'
/// lists. The exact test's answers are kept, one bit per candidate cell, each triangle's
/// bits in words of its own (no two tasks write a word): the filling pass reads them.
class CellInserter {
 public:
  CellInserter(GridData& g, const Scene& scene, const std::vector<CellRange>& ranges, bool exact)
      : g_(g), scene_(scene), valid_(scene.valid_prims()), ranges_(ranges), exact_(exact) {
    memo_start_.resize(exact ? valid_.size() + 1 : 0);
    for (size_t k = 0; exact && k < valid_.size(); ++k)
      memo_start_[k + 1] = memo_start_[k] + (ranges[k].cells() + 63) / 64;
    memo_.resize(exact ? memo_start_.back() : 0);
  }

  /// fn(cell) for every cell triangle `k` (of valid_prims()) goes into, in increasing
  /// linear index (x fastest); the second pass reads the first one's memo.
  template <class Fn>
  void for_each_cell(size_t k, bool second_pass, Fn&& fn) {
    if (exact_)
      insert_exact(g_, scene_, valid_[k], ranges_[k], memo_.data() + memo_start_[k], second_pass, fn);
    else
      insert_bbox(g_, ranges_[k], fn);
  }
  /// One more triangle in cell c: its slot (in the counting pass, the count so far).
  uint32_t bump(size_t c) { return par::fetch_add(g_.cell_start[c + 1], uint32_t(1)); }

 private:
  GridData& g_;
  const Scene& scene_;
  const std::vector<uint32_t>& valid_;
  const std::vector<CellRange>& ranges_;
  const bool exact_;
  std::vector<size_t> memo_start_;
  std::vector<uint64_t> memo_;
};

/// The counting pass: cell_start[c + 1] = the triangles of cell c. Recorded: serially in
/// triangle order, one step per triangle, the cells of its box range it is counted into.
/// False when cancelled.
template <class Sink>
bool count_cells(CellInserter& inserter, const Scene& scene, const std::vector<CellRange>& ranges,
                 BuildControl* control, Sink& sink) {
  const std::vector<uint32_t>& valid = scene.valid_prims();
  const auto bump = [&](size_t c) { return inserter.bump(c); };
  ProgressSpan counting(control, 0.1, 0.55);
  if constexpr (Sink::kRecords) {
    std::vector<uint32_t> stored;
    for (size_t k = 0; k < valid.size(); ++k) {
      if (k % 4096 == 0 && !counting.advance(double(k) / double(valid.size()))) return false;
      if (!sink.records(0)) {
        inserter.for_each_cell(k, false, bump);
        continue;
      }
      stored.clear();
      inserter.for_each_cell(k, false, [&](size_t c) {
        bump(c);
        stored.push_back(uint32_t(c));
      });
      const int lo[3] = {ranges[k].lo[0], ranges[k].lo[1], ranges[k].lo[2]};
      const int hi[3] = {ranges[k].hi[0], ranges[k].hi[1], ranges[k].hi[2]};
      sink.grid_insert(valid[k], lo, hi, stored.data(), stored.size());
    }
    if (counting.cancelled()) return false;
  } else {
    if (!for_each_prim_batch(valid.size(), counting, [&](size_t k) { inserter.for_each_cell(k, false, bump); }))
      return false;
  }
  counting.finish();
  return true;
}

/// Turns the counts into starts (cell_start[c + 1] = the start of c); returns the total.
uint32_t starts_from_counts(GridData& g) {
  uint32_t run = 0;
  for (size_t c = 0; c < g.cell_count(); ++c) {
    const uint32_t count = g.cell_start[c + 1];
    g.cell_start[c + 1] = run;
    run += count;
  }
  return run;
}

/// The filling pass: each triangle into its cells' lists, after which cell_start[c + 1] is
/// the end of c. The order within a cell depends on the threads: sorting each cell restores
/// the serial fill's (valid_prims() ascends). False when cancelled.
bool fill_cells(CellInserter& inserter, GridData& g, const Scene& scene, BuildControl* control) {
  const std::vector<uint32_t>& valid = scene.valid_prims();
  ProgressSpan filling(control, 0.55, 1.0);
  if (!for_each_prim_batch(valid.size(), filling, [&](size_t k) {
        inserter.for_each_cell(k, true, [&](size_t c) { g.prim_ids[inserter.bump(c)] = valid[k]; });
      }))
    return false;
  par::parallel_for(par::blocked_range<size_t>(0, g.cell_count(), 4096), [&](const par::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c < r.end(); ++c) {
      const auto begin = g.prim_ids.begin() + g.cell_start[c], end = g.prim_ids.begin() + g.cell_start[c + 1];
      if (!std::is_sorted(begin, end)) std::sort(begin, end);
    }
  });
  filling.finish();
  return true;
}

/// build_grid() for one sink: NullBuildSink (the normal, parallel build) or BuildRecorder
/// (the same grid, the insertion pass serial in triangle order so the steps come in order).
template <class Sink>
Result<GridData> build_grid_with(const Scene& scene, const GridConfig& config, BuildControl* control, Sink& sink) {
  GridData g;
  const std::vector<uint32_t>& valid = scene.valid_prims();
  if (build_cancelled(control)) return cancelled_error();
  if (valid.empty()) {
    g.cell_start = {0, 0};
    sink.scene_box(g.bounds);
    sink.done(g.cell_count());
    return g;
  }
  for (uint32_t prim : valid) g.bounds.extend(scene.triangle_bounds(prim));
  sink.scene_box(g.bounds);
  if (Status set = set_resolution(g, scene, config); !set) return set.error();
  auto ranges = fit_references(g, scene, config);
  if (!ranges) return ranges.error();
  if constexpr (Sink::kRecords) {
    const std::array<double, 4> values =
        resolution_terms(config, DVec3(g.bounds.extent()), valid.size(), scene.planar() ? 2 : 3);
    sink.grid_resolution(g.bounds, values.data(), g.res.data());
  }

  // Counting sort into CSR: cell_start[c + 1] counts, then holds the start of c, then
  // (after the fill) the end of c = the start of c + 1. Both passes run over the triangles
  // in parallel with atomic cell counters: the counts do not depend on the order, and the
  // fill's order within a cell, which does, is restored by sorting each cell afterwards.
  const size_t cells = g.cell_count();
  g.cell_start.assign(cells + 1, 0);
  CellInserter inserter(g, scene, ranges.value(), config.insertion == GridInsertion::Exact);
  report_progress(control, 0.1);
  if (build_cancelled(control)) return cancelled_error();
  if (!count_cells(inserter, scene, ranges.value(), control, sink)) return cancelled_error();
  const uint32_t run = starts_from_counts(g);
  g.prim_ids.resize(run);
  if (!fill_cells(inserter, g, scene, control)) return cancelled_error();
  ACCEL_CHECK(g.cell_start[cells] == run);
  sink.done(cells);
  return g;
}

}  // namespace

Result<GridData> build_grid(const Scene& scene, const GridConfig& config, BuildControl* control,
                            BuildRecorder* recorder) {
  if (recorder) return build_grid_with(scene, config, control, *recorder);
  NullBuildSink sink;
  return build_grid_with(scene, config, control, sink);
}

const ParamTable<UniformGridOptions>& UniformGrid::param_table() {
  using O = UniformGridOptions;
  static const auto table =
      ParamTable<O>()
          .choice("resolution", [](O& o) -> auto& { return o.build.rule; },
                  std::vector<std::pair<std::string, GridResolutionRule>>{{"cbrt", GridResolutionRule::Cbrt},
                                                                         {"avgsize", GridResolutionRule::AvgSize}},
                  "How cells are sized when res is not given: cbrt = lambda*cbrt(N) cells per axis of a cube-shaped "
                  "scene (lambda^3*N cuboid-like cells in all), avgsize = cell edge of the mean triangle bbox extent "
                  "/ lambda.")
          .number("lambda", [](O& o) -> auto& { return o.build.lambda; }, 0.01, 16,
                  "Per-axis factor of the resolution rule (lambda=2: 2*cbrt(N) cells per axis of a cube, 8 cells per "
                  "triangle); a result over the memory budget is shrunk to fit.")
          .int3("res", [](O& o) -> auto& { return o.build.res; }, 1, kGridMaxRes,
                "Cells per axis NX,NY,NZ; when given it overrides resolution and lambda (at most 2^26 cells in all).")
          .choice("insert", [](O& o) -> auto& { return o.build.insertion; },
                  std::vector<std::pair<std::string, GridInsertion>>{{"bbox", GridInsertion::Bbox},
                                                                    {"exact", GridInsertion::Exact}},
                  "Cells a triangle is stored in: every cell of its bounding box (the lecture's choice), or only the "
                  "cells it overlaps (Akenine-Moller 2001 test: slower build, fewer references, faster queries).")
          .choice("mailbox", &O::mailbox, std::vector<std::pair<std::string, bool>>{{"off", false}, {"on", true}},
                  "Skip triangles the ray already tested in an earlier cell (a 32-entry per-ray table on the stack).");
  return table;
}

Status UniformGrid::build_impl(const Scene& scene, const ParamSet& params, BuildControl* control, BuildRecorder* recorder) {
  scene_ = &scene;
  UniformGridOptions options = param_table().apply(params);
  GridConfig& config = options.build;
  config.explicit_res = params.is_set("res");  // a given res overrides the rule
  config.memory_limit = build_memory_limit(control);
  mailbox_ = options.mailbox;

  auto built = build_grid(scene, config, control, recorder);
  if (!built) {
    grid_ = GridData{};
    grid_.cell_start = {0, 0};
    stats_ = BuildStats{};
    return built.error();
  }
  grid_ = std::move(built.value());
  const DVec3 pad(grid_.pad);
  lo_ = DVec3(grid_.bounds.min) - pad;
  hi_ = DVec3(grid_.bounds.max) + pad;

  stats_ = BuildStats{};
  const size_t cells = grid_.cell_count();
  stats_.nodes = cells;
  stats_.prims = scene.valid_prims().size();
  stats_.prim_references = grid_.prim_ids.size();
  stats_.memory_bytes = grid_.cell_start.size() * sizeof(uint32_t) + grid_.prim_ids.size() * sizeof(uint32_t);
  for (size_t c = 0; c < cells; ++c) stats_.add_leaf(grid_.cell_start[c + 1] - grid_.cell_start[c]);
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.4g x %.4g x %.4g", grid_.cell_size.x, grid_.cell_size.y, grid_.cell_size.z);
  stats_.extra = {{"resolution", res_text(grid_.res)},
                  {"cell_size", buf},
                  {"rule", config.explicit_res ? "res (explicit)"
                                               : std::string(config.rule == GridResolutionRule::Cbrt ? "cbrt" : "avgsize") +
                                                     ", lambda " + format_number(config.lambda) +
                                                     (grid_.clamped_to_budget ? ", shrunk to the memory budget" : "")},
                  {"insert", config.insertion == GridInsertion::Exact ? "exact" : "bbox"},
                  {"mailbox", mailbox_ ? "on" : "off"}};
  return {};
}

Aabb UniformGrid::cell_box(NodeId id) const {
  const int nx = grid_.res[0], ny = grid_.res[1];
  const int idx[3] = {int(id % uint32_t(nx)), int((id / uint32_t(nx)) % uint32_t(ny)), int(id / uint32_t(nx * ny))};
  DVec3 lo, hi;
  cell_bounds(grid_, idx, &lo, &hi);
  Aabb box;
  box.min = Vec3(lo);
  box.max = Vec3(hi);
  return box;
}

void UniformGrid::for_each_node(const std::function<void(const NodeView&)>& fn) const {
  const size_t cells = grid_.cell_count();
  if (grid_.prim_ids.empty()) return;
  for (size_t c = 0; c < cells; ++c)
    if (grid_.cell_start[c + 1] != grid_.cell_start[c]) fn(node_view(NodeId(c)));
}

NodeView UniformGrid::node_view(NodeId id) const {
  NodeView v;
  v.id = id;
  v.leaf = true;
  if (grid_.prim_ids.empty() || size_t(id) >= grid_.cell_count()) return v;
  v.prim_count = grid_.cell_start[id + 1] - grid_.cell_start[id];
  v.box = cell_box(id);
  return v;
}

std::vector<uint32_t> UniformGrid::node_prims(NodeId id) const {
  if (grid_.prim_ids.empty() || size_t(id) >= grid_.cell_count()) return {};
  return std::vector<uint32_t>(grid_.prim_ids.begin() + grid_.cell_start[id],
                               grid_.prim_ids.begin() + grid_.cell_start[id + 1]);
}

}  // namespace accel
