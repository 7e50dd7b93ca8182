// Lecturer's test solution: the uniform grid of the lecture ("Uniform Grid"), written the way
// a student would: the cube-root resolution rule, triangles inserted by their bounding boxes,
// and the 3D-DDA of Amanatides & Woo (1987) with the rule that a hit found in a cell ends the
// walk only when it lies inside that cell.
//
// Planted bug (off by default), compiled as a variant by the kit's tests:
//   PLANT_BUG_GRID_TIE  the DDA picks the axis to step with strict comparisons, so when
//                       tMaxX == tMaxY (< tMaxZ) it steps along z: diagonal rays walk off
//                       their path.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "accelviz_student.h"

#ifndef SOLUTION_NAME
#define SOLUTION_NAME "sol_grid"
#endif

using namespace accelviz;

namespace {

class SolutionGrid : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    scene_ = &scene;
    cells_.clear();
    std::vector<uint32_t> prims;
    Box box;
    for (uint32_t p = 0; p < scene.size(); ++p) {
      if (scene.is_degenerate(p)) continue;  // zero-area: never hit
      prims.push_back(p);
      box.grow(scene.box(p));
    }
    if (prims.empty()) {  // an empty scene: one empty cell, every ray misses
      box_ = scene.bounds().empty() ? Box{Vec3(0.0f), Vec3(0.0f)} : scene.bounds();
      res_[0] = res_[1] = res_[2] = 1;
      size_ = Vec3(0.0f);
      log.grid_resolution(box_, 1, 1, 1);
      cells_.assign(1, {});
      empty_ = true;
      return;
    }
    empty_ = false;
    box_ = box;

    // Resolution: about lambda * cbrt(N) cells along the longest axis (lambda = 2), the
    // other axes in proportion so that the cells are cube-like; at least 1 per axis (a flat
    // scene gets one layer), and at most kMaxCells cells in all.
    const Vec3 e = box_.extent();
    const float e_max = std::max(e.x, std::max(e.y, e.z));
    float per_axis = kLambda * std::cbrt(float(prims.size()));
    for (;;) {
      size_t cells = 1;
      for (int a = 0; a < 3; ++a) {
        res_[a] = std::max(1, int(std::lround(per_axis * e[a] / e_max)));
        cells *= size_t(res_[a]);
      }
      if (cells <= kMaxCells) break;
      per_axis *= 0.9f;  // too many cells: shrink
    }
    for (int a = 0; a < 3; ++a) size_[a] = e[a] / float(res_[a]);
    log.grid_resolution(box_, res_[0], res_[1], res_[2]);
    cells_.assign(size_t(res_[0]) * size_t(res_[1]) * size_t(res_[2]), {});

    // Insert each triangle into every cell its bounding box overlaps. The box is widened by
    // a tiny epsilon: touching a cell counts (closed intervals), and rounding in the DDA can
    // never lose a triangle that lies on a cell boundary.
    for (uint32_t p : prims) {
      const Box& b = scene.box(p);
      int lo[3], hi[3];
      for (int a = 0; a < 3; ++a) {
        const float eps = 1e-4f * size_[a] + 1e-6f * std::max(std::fabs(b.lo[a]), std::fabs(b.hi[a]));
        lo[a] = cell_of(a, b.lo[a] - eps);
        hi[a] = cell_of(a, b.hi[a] + eps);
      }
      for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
          for (int x = lo[0]; x <= hi[0]; ++x) {
            cells_[index(x, y, z)].push_back(p);
            log.cell_filled(x, y, z, p);
          }
    }
  }

  Hit intersect(const Ray& ray, TraversalLog log) const override {
    Hit closest;
    closest.t = ray.tmax;
    if (empty_) return finish(closest);
    // Clip the ray to the grid's box: it is inside over [t0, t1].
    float t0, t1;
    if (!intersect_box(ray, box_, ray.tmin, ray.tmax, t0, t1)) return finish(closest);

    // 3D-DDA set-up: the cell where the ray enters, and per axis the step (+1, -1 or 0),
    // tMax (t at which the ray crosses the next cell boundary on that axis) and tDelta (t
    // to cross one whole cell on that axis).
    int cell[3], step[3];
    float t_max[3], t_delta[3];
    for (int a = 0; a < 3; ++a) {
      cell[a] = cell_of(a, ray.origin[a] + t0 * ray.direction[a]);
      if (ray.direction[a] > 0.0f) {
        step[a] = 1;
      } else if (ray.direction[a] < 0.0f) {
        step[a] = -1;
      } else {
        step[a] = 0;  // parallel to this axis: never crosses its boundaries
      }
      t_max[a] = next_crossing(ray, a, cell[a], step[a]);
      t_delta[a] = step[a] == 0 ? kInfinity : size_[a] * std::fabs(ray.inv_direction[a]);
    }

    float t_enter = t0;
    for (;;) {
      const float t_exit = std::min(std::min(t_max[0], t_max[1]), std::min(t_max[2], t1));
      log.enter_cell(cell[0], cell[1], cell[2], t_enter, t_exit);
      log.grid_dda(cell, step, t_max, t_delta);
      for (uint32_t p : cells_[index(cell[0], cell[1], cell[2])]) test_triangle(ray, *scene_, p, closest, log);
      // A hit found here ends the walk only if it lies inside this cell: a triangle stored
      // here may be hit beyond the cell, where another cell may hold a nearer one (the
      // lecture's trap). A tiny relative slack for rounding at the boundary.
      if (closest.valid() && closest.t <= t_exit + 1e-6f * std::fabs(t_exit)) return finish(closest);

      // Step to the next cell along the axis whose boundary comes first (smallest tMax).
      int axis;
#ifdef PLANT_BUG_GRID_TIE
      if (t_max[0] < t_max[1] && t_max[0] < t_max[2])
        axis = 0;
      else if (t_max[1] < t_max[0] && t_max[1] < t_max[2])
        axis = 1;
      else
        axis = 2;
#else
      if (t_max[0] <= t_max[1] && t_max[0] <= t_max[2])
        axis = 0;
      else if (t_max[1] <= t_max[2])
        axis = 1;
      else
        axis = 2;
#endif
      if (t_max[axis] > t1) break;  // the ray ends (or leaves the grid) inside this cell
      cell[axis] += step[axis];
      if (step[axis] == 0 || cell[axis] < 0 || cell[axis] >= res_[axis]) break;  // outside the grid
      t_enter = t_max[axis];
      // tMax += tDelta, but computed from the boundary itself so no rounding accumulates.
      t_max[axis] = next_crossing(ray, axis, cell[axis], step[axis]);
    }
    return finish(closest);
  }

 private:
  static constexpr float kLambda = 2.0f;
  static constexpr size_t kMaxCells = size_t(1) << 22;

  size_t index(int x, int y, int z) const {
    return size_t(x) + size_t(res_[0]) * (size_t(y) + size_t(res_[1]) * size_t(z));
  }

  /// The position of the cell boundary `k` (0 .. res) along `axis`.
  float boundary(int axis, int k) const { return box_.lo[axis] + float(k) * size_[axis]; }

  /// The cell (along `axis`) that coordinate `v` lies in, clamped to the grid.
  int cell_of(int axis, float v) const {
    if (!(size_[axis] > 0.0f)) return 0;  // a flat axis has one layer
    const float c = std::floor((v - box_.lo[axis]) / size_[axis]);
    if (!(c >= 0.0f)) return 0;
    return c >= float(res_[axis] - 1) ? res_[axis] - 1 : int(c);
  }

  /// t at which the ray leaves cell `c` along `axis` (the lecture's tMax).
  float next_crossing(const Ray& ray, int axis, int c, int step) const {
    if (step == 0) return kInfinity;
    const float b = boundary(axis, step > 0 ? c + 1 : c);
    return (b - ray.origin[axis]) * ray.inv_direction[axis];
  }

  const Scene* scene_ = nullptr;
  Box box_;
  Vec3 size_;  // a cell's edge lengths
  int res_[3] = {1, 1, 1};
  bool empty_ = true;
  std::vector<std::vector<uint32_t>> cells_;
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(SolutionGrid, SOLUTION_NAME, grid)
