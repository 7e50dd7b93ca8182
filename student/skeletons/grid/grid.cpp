// Assignment: the UNIFORM GRID of the lecture ("Uniform Grid"), traversed with the 3D-DDA of
// Amanatides & Woo (1987). Fill in build() and intersect() where it says TODO; the log calls
// are already where the lecture's steps happen (keep them there: the viewer animates them
// and `check` reads them). As it stands it builds one empty cell and every ray misses.
//
// Build it into accelviz and check it:
//   scripts/run.sh --student student/skeletons/grid
//   build/bin/accelviz-cli check --structure my_grid
// The kit's reference: student/accelviz_student.h; a complete example: student/example/.
#include <algorithm>
#include <cmath>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class MyGrid : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    scene_ = &scene;
    // TODO 1: "Calculate BBox of the scene": the triangles that are not degenerate
    //         (scene.is_degenerate(p): zero-area triangles are never hit) and the box around
    //         them. (An empty scene: keep one empty cell, every ray misses.)
    std::vector<uint32_t> prims;
    box_ = scene.bounds().empty() ? Box{Vec3(0.0f), Vec3(0.0f)} : scene.bounds();

    // TODO 2: "Choose a (suitable) grid resolution (n_x, n_y, n_z)": resolution =
    //         lambda * cbrt(N) (lambda about 2) cells along the box, the cells cube-like, at
    //         least 1 per axis (a flat scene is 1 cell thick) and not millions of cells.
    res_[0] = res_[1] = res_[2] = 1;
    log.grid_resolution(box_, res_[0], res_[1], res_[2]);
    cells_.assign(size_t(res_[0]) * size_t(res_[1]) * size_t(res_[2]), {});

    // "For each cell store all objects intersecting that cell"; "use bbox of objects".
    for (uint32_t p : prims) {
      // TODO 3: the cells its bounding box overlaps, lo[a] .. hi[a] along each axis (closed:
      //         a box touching a cell counts; mind rounding at the cell boundaries).
      int lo[3] = {0, 0, 0}, hi[3] = {-1, -1, -1};
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
    closest.t = ray.tmax;  // closest_hit: at first "as far as the ray goes"

    // TODO 4: clip the ray to the grid's box: intersect_box(ray, box_, ray.tmin, ray.tmax,
    //         t0, t1); a miss (or an empty grid) -> return finish(closest).
    float t0 = ray.tmin, t1 = ray.tmax;

    // TODO 5: the DDA set-up. The cell (X, Y, Z) containing the entry point o + t0*d; per
    //         axis stepX = +1 / -1 / 0 (the sign of d), tMaxX = the t at which the ray
    //         crosses the next cell boundary in x (inf if d.x == 0), tDeltaX = the t it takes
    //         to cross one cell in x (cell width * |ray.inv_direction.x|).
    int cell[3] = {0, 0, 0}, step[3] = {0, 0, 0};
    float t_max[3] = {kInfinity, kInfinity, kInfinity}, t_delta[3] = {kInfinity, kInfinity, kInfinity};
    float t_enter = t0;
    bool inside = false;  // TODO: true while (X, Y, Z) is a cell of the grid

    while (inside) {
      // The ray is inside this cell until the first boundary it crosses (or t1).
      const float t_exit = std::min(std::min(t_max[0], t_max[1]), std::min(t_max[2], t1));
      log.enter_cell(cell[0], cell[1], cell[2], t_enter, t_exit);
      log.grid_dda(cell, step, t_max, t_delta);

      // "Is any of the objects in the cell hit by the ray?" (test_triangle keeps the closest)
      for (uint32_t p : cells_[index(cell[0], cell[1], cell[2])]) test_triangle(ray, *scene_, p, closest, log);

      // TODO 6: "Yes: return closest hit" -- but only if that hit lies INSIDE this cell
      //         (closest.t <= t_exit): a triangle stored here may be hit beyond the cell,
      //         where another cell may hold a nearer one (the lecture's trap). Mind rounding:
      //         a hit exactly on the boundary is inside.

      // TODO 7: "No: proceed to next cell", the lecture's loop:
      //           if (tMaxX < tMaxY) {
      //             if (tMaxX < tMaxZ) { X = X + stepX; if (X == justOutX) return NIL; tMaxX += tDeltaX; }
      //             else               { Z = Z + stepZ; if (Z == justOutZ) return NIL; tMaxZ += tDeltaZ; }
      //           } else {
      //             if (tMaxY < tMaxZ) { Y = Y + stepY; if (Y == justOutY) return NIL; tMaxY += tDeltaY; }
      //             else               { Z = Z + stepZ; if (Z == justOutZ) return NIL; tMaxZ += tDeltaZ; }
      //           }
      //         "return(NIL)": the ray left the grid -- leave the loop (the closest hit found
      //         so far is the answer). Leave it too when the next boundary lies beyond t1 (the
      //         ray ends in this cell). The next cell's t_enter is the tMax you stepped at.
      inside = false;
    }
    return finish(closest);  // every cell walked: the closest hit found, or a miss
  }

 private:
  size_t index(int x, int y, int z) const {
    return size_t(x) + size_t(res_[0]) * (size_t(y) + size_t(res_[1]) * size_t(z));
  }

  const Scene* scene_ = nullptr;
  Box box_;                                   // the grid's box
  int res_[3] = {1, 1, 1};                    // n_x, n_y, n_z
  std::vector<std::vector<uint32_t>> cells_;  // per cell (index(x, y, z)): its triangles
  // TODO: whatever else you need, e.g. the cell size per axis.
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(MyGrid, "my_grid", grid)
