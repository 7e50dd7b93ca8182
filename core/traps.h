#pragma once
// The lecture's traps, demonstrated: small scenes with one ray each where a naive traversal
// that stops at the first leaf or cell with a hit gives the wrong answer.
//   pq    BVH, priority queue: "the closest ray-BV intersection and the closest
//         ray-primitive intersection can occur in different BVs"
//   kd    kd-tree: a triangle straddling the split plane is hit beyond t_split while a
//         nearer triangle waits in the far child (why the hit is checked against t_split)
//   grid  uniform grid: a hit found in a cell but lying beyond it (why the closest hit must
//         lie in the current cell before the walk stops)
// The structures stay exact: the naive answer is computed from the recorded steps of the
// real traversal, for display only.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geometry.h"
#include "result.h"
#include "scene.h"
#include "trace.h"

namespace accel {

/// One demonstration: its scene (a procedural scene, "procedural:trap_NAME"), the structure
/// and parameters that show the trap, and the ray.
struct TrapDemo {
  std::string name;                 ///< "pq", "kd", "grid"
  std::string title;                ///< one line for the viewer
  std::string explanation;          ///< why the naive traversal goes wrong (one or two sentences)
  std::string scene;                ///< "procedural:trap_pq", ... (make_procedural_scene knows it)
  std::string structure;            ///< registry name
  std::vector<std::string> params;  ///< key=value, as accelviz-cli takes them
  Ray ray;
};

/// "pq", "kd", "grid".
std::vector<std::string> trap_names();
/// The demonstration named `name`; an error listing the names otherwise.
Result<TrapDemo> trap_demo(std::string_view name);
/// The scene of trap `name` ("pq", ...) for make_procedural_scene's "trap_NAME"; error when
/// unknown.
Result<Scene> make_trap_scene(std::string_view name);

/// What a naive traversal would answer that stops at the first leaf or grid cell in which
/// a triangle test hits, taking the closest hit among that leaf's tests, without checking
/// that the hit lies inside the leaf (before t_split, inside the cell) or that no pending
/// node could hold a nearer one.
struct NaiveAnswer {
  bool hit = false;   ///< false: no test hit at all (the naive traversal misses too)
  int32_t prim = -1;
  float t = kInf;
  size_t stop_step = 0;  ///< the step at which it would stop: the last test of that leaf
};
/// Computed from the recorded events of the real traversal.
NaiveAnswer naive_first_leaf_hit(std::span<const TraceEvent> events);
/// "naive hit PRIM T" or "naive miss" (T printed with %.9g, as print-hit does).
std::string naive_line(const NaiveAnswer& answer);

}  // namespace accel
