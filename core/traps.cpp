#include "traps.h"

#include <cstdio>
#include <utility>

namespace accel {
namespace {

// All three traps use one figure, so the viewer shows the same two triangles fooling each
// naive traversal in its own way. The ray runs along +x at y = z = 0 from x = -1:
//   prim 0, "slanted": the plane x = 2 (2 - y) between (0, 2, +-1.5) and (6, -1, 0). Its box
//           spans x in [0, 6], so the ray enters it first (t = 1), but meets the triangle
//           itself only at x = 4 (t = 5), inside it at |z| <= 0.5.
//   prim 1, "small": the plane x = 3.5 + 0.5 y, x in [3.35, 3.65], met at x = 3.5 (t = 4.5),
//           inside it at |z| <= 0.15: nearer than prim 0's hit, but in a box entered later
//           (t = 4.35), beyond the kd-tree's and the grid's cut at x = 3.
/// x of the ray's origin: one unit before the scene, so the ray is seen entering it.
constexpr float kRayStart = -1.0f;

/// The figure above, named `name`.
Scene slanted_and_small(std::string name) {
  std::vector<Vec3> positions = {
      {0.0f, 2.0f, -1.5f},    {0.0f, 2.0f, 1.5f},     {6.0f, -1.0f, 0.0f},  // prim 0: slanted
      {3.35f, -0.3f, -0.3f},  {3.35f, -0.3f, 0.3f},   {3.65f, 0.3f, 0.0f},  // prim 1: small
  };
  std::vector<UVec3> triangles = {{0, 1, 2}, {3, 4, 5}};
  return Scene(std::move(positions), std::move(triangles), std::move(name));
}

/// One demonstration as declared: what TrapDemo holds besides the scene spec and the ray,
/// which all three share.
struct TrapEntry {
  const char* name;
  const char* title;
  const char* explanation;
  const char* structure;
  std::vector<std::string> params;
};

/// The three demonstrations. The parameters make the trees the figure needs:
///  pq    width=2 and leaf_size=1: a binary tree with one triangle per leaf, so the two
///        boxes are two queue entries;
///  kd    split=middle, max_depth=1: one split at the middle of x in [0, 6], x = 3, which
///        the slanted triangle straddles (the default SAH keeps two triangles in one leaf,
///        since no plane costs less than testing both, and a larger ci splits at x = 3.35
///        into a deeper tree that shows the same thing less plainly);
///  grid  res=2,1,1: two cells, x in [0, 3] and [3, 6].
const std::vector<TrapEntry>& trap_entries() {
  static const std::vector<TrapEntry> entries = {
      {"pq", "BVH priority queue: the nearest box need not hold the nearest hit",
       "The slanted triangle's leaf box is entered first (t=1) but the triangle is hit only at t=5; the small "
       "triangle's box is entered later (t=4.35) and hit at t=4.5. \"The closest ray-BV intersection and the "
       "closest ray-primitive intersection can occur in different BVs\": the queue must run until its nearest "
       "pending box lies beyond the closest hit.",
       "bvh",
       {"width=2", "builder=sah", "leaf_size=1", "traversal=pqueue"}},
      {"kd", "kd-tree: a hit beyond t_split in the near child",
       "The slanted triangle straddles the split plane x=3 (t_split=4), so the near leaf holds it, but the ray "
       "meets it beyond the plane (t=5); the small triangle in the far child is hit at t=4.5. A hit in the near "
       "child ends the query only when it lies before t_split.",
       "kdtree",
       {"split=middle", "axis=longest", "max_depth=1", "clip=on"}},
      {"grid", "uniform grid: a hit found in a cell but lying beyond it",
       "The slanted triangle is stored in the first cell the ray enters (x in [0,3], left at t=4), but the ray "
       "meets it in the next cell (t=5), where the small triangle is hit nearer (t=4.5). The walk may stop only "
       "when the closest hit lies inside the cell just processed.",
       "grid",
       {"res=2,1,1", "insert=exact"}},
  };
  return entries;
}

/// The entry named `name`, or nullptr.
const TrapEntry* find_entry(std::string_view name) {
  for (const TrapEntry& e : trap_entries())
    if (name == e.name) return &e;
  return nullptr;
}

/// "unknown trap 'NAME' (valid: pq, kd, grid)".
Error unknown_trap(std::string_view name) {
  std::string valid;
  for (const TrapEntry& e : trap_entries()) valid += std::string(valid.empty() ? "" : ", ") + e.name;
  return make_error("unknown trap '" + std::string(name) + "' (valid: " + valid + ")");
}

}  // namespace

std::vector<std::string> trap_names() {
  std::vector<std::string> names;
  for (const TrapEntry& e : trap_entries()) names.emplace_back(e.name);
  return names;
}

Result<TrapDemo> trap_demo(std::string_view name) {
  const TrapEntry* e = find_entry(name);
  if (!e) return unknown_trap(name);
  TrapDemo demo;
  demo.name = e->name;
  demo.title = e->title;
  demo.explanation = e->explanation;
  demo.scene = "procedural:trap_" + demo.name;
  demo.structure = e->structure;
  demo.params = e->params;
  demo.ray.org = Vec3(kRayStart, 0.0f, 0.0f);
  demo.ray.dir = Vec3(1.0f, 0.0f, 0.0f);
  demo.ray.tmin = 0.0f;
  demo.ray.tmax = kInf;
  return demo;
}

Result<Scene> make_trap_scene(std::string_view name) {
  if (!find_entry(name)) return unknown_trap(name);
  return slanted_and_small("procedural:trap_" + std::string(name));
}

NaiveAnswer naive_first_leaf_hit(std::span<const TraceEvent> events) {
  NaiveAnswer answer;
  if (events.empty()) return answer;
  // The current leaf's run: its closest hit so far and its last test. A traversal without
  // Visit events (none here, but a recorder may start mid-query) counts as one leaf.
  NaiveAnswer run;
  for (size_t i = 0; i < events.size(); ++i) {
    const TraceEvent& e = events[i];
    if (e.kind == TraceEventKind::TestPrim) {
      run.stop_step = i;
      if (e.hit && (!run.hit || e.t0 < run.t)) {  // ties keep the first test
        run.hit = true;
        run.prim = e.prim;
        run.t = e.t0;
      }
    } else if (e.kind == TraceEventKind::Visit || e.kind == TraceEventKind::EnterCell) {
      if (run.hit) return run;  // the leaf just tested had a hit: the naive traversal stops there
      run = NaiveAnswer{};
    }
    // NewClosest follows its test inside the run; Push, Pop, Cull and Done end nothing by
    // themselves: the next Visit / EnterCell (or the end) closes the run.
  }
  if (run.hit) return run;
  answer.stop_step = events.size() - 1;
  return answer;
}

std::string naive_line(const NaiveAnswer& answer) {
  if (!answer.hit) return "naive miss";
  char buf[64];
  std::snprintf(buf, sizeof buf, "naive hit %d %.9g", answer.prim, double(answer.t));
  return buf;
}

}  // namespace accel
