// The traversal variables the real loops record (trace.h: GridDdaVars, KdSplitVars,
// KdExitVars, OctreeOrderVars) against values computed here independently, in double, from
// the built structure's data and node views -- never by running a traversal -- on
// hand-checked rays; the hierarchies' pending keys against their volumes' entry distances;
// Structure::node_children; describe_vars.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "ray_gen.h"
#include "registry.h"
#include "scene.h"
#include "structures/kd_tree.h"
#include "structures/octree.h"
#include "structures/uniform_grid.h"
#include "test_support.h"
#include "trace_player.h"

namespace accel {
namespace {

using testing::make_ray;
constexpr double kDInf = std::numeric_limits<double>::infinity();

static_assert(!NullSink::kRecords && !StatsSink::kRecords,
              "only recording sinks receive vars: the fast and the counting paths compute none");

/// The fast path's answer (through the interface, whose intersect() has the default stats).
Hit fast_hit(const Structure& s, const Ray& ray) { return s.intersect(ray); }

std::unique_ptr<Structure> build(const std::string& name, const Scene& scene, const std::vector<std::string>& params) {
  auto built = build_structure(name, scene, params);
  EXPECT_TRUE(built.ok()) << name << ": " << (built.ok() ? "" : built.error().message);
  return built ? std::move(built.value()) : nullptr;
}

/// |got - want| within `rel` of max(1, |want|), infinities equal.
::testing::AssertionResult near_rel(double got, double want, double rel = 1e-6) {
  if (std::isinf(want) || std::isinf(got)) {
    if (got == want) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "got " << got << ", want " << want;
  }
  if (std::abs(got - want) <= rel * std::max(1.0, std::abs(want))) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "got " << got << ", want " << want << " (rel " << rel << ")";
}

/// The ray's interval [t0, t1] inside `box` clipped to [tmin, tmax], in double; false on a miss.
bool slab(const Ray& ray, const Aabb& box, double* t0, double* t1) {
  double lo = ray.tmin, hi = ray.tmax;
  for (int a = 0; a < 3; ++a) {
    const double o = ray.org[a], d = ray.dir[a];
    if (d == 0.0) {
      if (o < box.min[a] || o > box.max[a]) return false;
      continue;
    }
    double ta = (double(box.min[a]) - o) / d, tb = (double(box.max[a]) - o) / d;
    if (ta > tb) std::swap(ta, tb);
    lo = std::max(lo, ta);
    hi = std::min(hi, tb);
  }
  *t0 = lo;
  *t1 = hi;
  return lo <= hi;
}

/// The closest hit known after events[0..step]: the last NewClosest's t (`none` before one:
/// the traversals' running closest t is ray.tmax, the highlight's inf).
float closest_after(const std::vector<TraceEvent>& ev, size_t step, float none = kInf) {
  float t = none;
  for (size_t i = 0; i <= step && i < ev.size(); ++i)
    if (ev[i].kind == TraceEventKind::NewClosest) t = ev[i].t0;
  return t;
}

/// Index of the last event of `kind` at or before `step` (ev.size() if none).
size_t last_of(const std::vector<TraceEvent>& ev, size_t step, TraceEventKind kind) {
  for (size_t i = std::min(step + 1, ev.size()); i-- > 0;)
    if (ev[i].kind == kind) return i;
  return ev.size();
}

// =======================================================================================
// Grid: the 3D-DDA's variables

/// Two corner triangles span the box [0,4]^3 (cells of 1 with res=4,4,4); a third, in the
/// plane x = 2.5 over y, z in [1, 3], is the target of the hitting ray.
Scene grid_scene() {
  std::vector<Vec3> p = {{0, 0, 0},   {0.5f, 0, 0}, {0, 0.5f, 0},  {4, 4, 4},       {3.5f, 4, 4},
                         {4, 3.5f, 4}, {2.5f, 1, 1}, {2.5f, 3, 1}, {2.5f, 2, 3}};
  return Scene(std::move(p), {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}}, "grid_vars");
}

/// One cell of the independent walk.
struct DdaStep {
  int cell[3];
  int step[3];
  double t_max[3];
  double t_delta[3];
  int next;
};

/// Amanatides & Woo's walk computed here from the grid's box, resolution and cell size, in
/// double: every cell the ray passes until it leaves the grid (the rays below avoid ties
/// between axes, so the next axis is the strict minimum).
std::vector<DdaStep> independent_walk(const GridData& g, const Ray& ray) {
  Aabb box = g.bounds;
  double t0, t1;
  if (!slab(ray, box, &t0, &t1)) return {};
  DdaStep s{};
  for (int a = 0; a < 3; ++a) {
    const int n = g.res[a];
    const double o = ray.org[a], d = ray.dir[a], lo = g.bounds.min[a], cs = g.cell_size[a];
    const double p = o + t0 * d;
    s.cell[a] = n == 1 ? 0 : std::clamp(int(std::floor((p - lo) / cs)), 0, n - 1);
    s.step[a] = n == 1 || d == 0.0 ? 0 : (d > 0.0 ? 1 : -1);
    s.t_delta[a] = s.step[a] ? cs / std::abs(d) : 0.0;
    s.t_max[a] = s.step[a] ? (lo + (s.cell[a] + (s.step[a] > 0)) * cs - o) / d : kDInf;
  }
  std::vector<DdaStep> walk;
  for (;;) {
    s.next = 0;
    for (int a = 1; a < 3; ++a)
      if (s.t_max[a] < s.t_max[s.next]) s.next = a;
    walk.push_back(s);
    const int a = s.next;
    if (s.step[a] == 0) break;
    s.cell[a] += s.step[a];
    if (s.cell[a] < 0 || s.cell[a] >= g.res[a]) break;
    s.t_max[a] = (double(g.bounds.min[a]) + (s.cell[a] + (s.step[a] > 0)) * g.cell_size[a] - ray.org[a]) / ray.dir[a];
  }
  return walk;
}

/// Checks the grid's recorded variables for `ray` against the independent walk; returns the
/// recorded ones.
std::vector<GridDdaVars> check_grid_ray(const UniformGrid& grid, const Ray& ray) {
  TraceRecorder rec;
  const Hit hit = grid.intersect_traced(ray, rec);
  const Hit fast = fast_hit(grid, ray);
  EXPECT_EQ(fast.prim, hit.prim);
  EXPECT_EQ(fast.t, hit.t);
  const GridData& g = grid.data();
  const std::vector<DdaStep> want = independent_walk(g, ray);
  std::vector<GridDdaVars> got;
  for (const RecordedVars& r : rec.recorded_vars()) {
    const auto* v = std::get_if<GridDdaVars>(&r.vars);
    EXPECT_NE(v, nullptr) << "a grid records only GridDdaVars";
    if (!v) continue;
    got.push_back(*v);
    // Recorded right after the EnterCell of the very cell they describe.
    const TraceEvent& e = rec.events()[r.event];
    EXPECT_EQ(e.kind, TraceEventKind::EnterCell);
    EXPECT_EQ(e.node, NodeId(v->cell[0] + g.res[0] * (v->cell[1] + g.res[1] * v->cell[2])));
  }
  const size_t cells = size_t(std::count_if(rec.events().begin(), rec.events().end(),
                                            [](const TraceEvent& e) { return e.kind == TraceEventKind::EnterCell; }));
  EXPECT_EQ(got.size(), cells);
  // The walk ends in the cell whose exit reaches the closest hit, or where the ray leaves.
  size_t expected = want.size();
  if (hit.valid())
    for (size_t k = 0; k < want.size(); ++k)
      if (want[k].t_max[want[k].next] >= hit.t) {
        expected = k + 1;
        break;
      }
  EXPECT_EQ(got.size(), expected);
  for (size_t k = 0; k < std::min(got.size(), want.size()); ++k) {
    SCOPED_TRACE("cell " + std::to_string(k));
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(got[k].cell[a], want[k].cell[a]) << "axis " << a;
      EXPECT_EQ(got[k].step[a], want[k].step[a]) << "axis " << a;
      EXPECT_TRUE(near_rel(got[k].t_max[a], want[k].t_max[a])) << "tMax axis " << a;
      EXPECT_TRUE(near_rel(got[k].t_delta[a], want[k].t_delta[a])) << "tDelta axis " << a;
    }
    EXPECT_EQ(got[k].next_axis, want[k].next);
  }
  return got;
}

const UniformGrid* as_grid(const Structure* s) { return dynamic_cast<const UniformGrid*>(s); }

TEST(StepVarsGrid, MissingRayWalksTheWholeGridAsComputed) {
  const Scene scene = grid_scene();
  auto s = build("grid", scene, {"res=4,4,4"});
  ASSERT_TRUE(s);
  const UniformGrid* grid = as_grid(s.get());
  ASSERT_NE(grid, nullptr);
  ASSERT_EQ(grid->data().res, (std::array<int, 3>{4, 4, 4}));
  ASSERT_EQ(grid->data().cell_size, DVec3(1.0));
  // Enters at x = 0 (t = 1) in cell (0, 3, 0), leaves at x = 4 (t = 5); crossings in x at
  // t = 2, 3, 4, 5, in y (down) at 7/3, in z at 16/11, 36/11: no two at once.
  const Ray ray = make_ray({-1.0f, 3.7f, 0.2f}, {1.0f, -0.3f, 0.55f});
  const auto got = check_grid_ray(*grid, ray);
  ASSERT_EQ(got.size(), 7u);  // 4 steps in x, 1 in y, 2 in z, plus the first cell
  // Hand-checked first cell: (0,3,0), steps (+1,-1,+1), tMax = (2, 7/3, 16/11),
  // tDelta = (1, 10/3, 20/11), z steps next.
  EXPECT_EQ(got[0].cell[0], 0);
  EXPECT_EQ(got[0].cell[1], 3);
  EXPECT_EQ(got[0].cell[2], 0);
  EXPECT_EQ(got[0].step[0], 1);
  EXPECT_EQ(got[0].step[1], -1);
  EXPECT_EQ(got[0].step[2], 1);
  EXPECT_FLOAT_EQ(got[0].t_max[0], 2.0f);
  EXPECT_NEAR(got[0].t_max[1], 7.0 / 3.0, 1e-5);
  EXPECT_NEAR(got[0].t_max[2], 16.0 / 11.0, 1e-5);
  EXPECT_FLOAT_EQ(got[0].t_delta[0], 1.0f);
  EXPECT_NEAR(got[0].t_delta[1], 10.0 / 3.0, 1e-5);
  EXPECT_NEAR(got[0].t_delta[2], 20.0 / 11.0, 1e-5);
  EXPECT_EQ(got[0].next_axis, 2);
  // Then (0,3,1) -> x at t=2 -> (1,3,1) -> y at 7/3 -> (1,2,1) -> x at 3 -> (2,2,1) -> z at
  // 36/11 -> (2,2,2) -> x at 4 -> (3,2,2), which the ray leaves through x = 4 at t = 5.
  const int cells[7][3] = {{0, 3, 0}, {0, 3, 1}, {1, 3, 1}, {1, 2, 1}, {2, 2, 1}, {2, 2, 2}, {3, 2, 2}};
  for (int k = 0; k < 7; ++k)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(got[size_t(k)].cell[a], cells[k][a]) << k << " " << a;
  EXPECT_EQ(got[6].next_axis, 0);
  EXPECT_FLOAT_EQ(got[6].t_max[0], 5.0f);
}

TEST(StepVarsGrid, NegativeDirectionsStepDown) {
  const Scene scene = grid_scene();
  auto s = build("grid", scene, {"res=4,4,4"});
  ASSERT_TRUE(s);
  const Ray ray = make_ray({5.0f, 3.7f, 3.9f}, {-1.0f, -0.4f, -0.6f});
  const auto got = check_grid_ray(*as_grid(s.get()), ray);
  ASSERT_FALSE(got.empty());
  EXPECT_EQ(got[0].cell[0], 3);
  EXPECT_EQ(got[0].cell[1], 3);
  EXPECT_EQ(got[0].cell[2], 3);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(got[0].step[a], -1);
  EXPECT_FLOAT_EQ(got[0].t_max[0], 2.0f);  // x = 3 at t = 2
}

TEST(StepVarsGrid, HittingRayStopsInTheCellOfTheHit) {
  const Scene scene = grid_scene();
  for (const char* mailbox : {"mailbox=on", "mailbox=off"}) {
    auto s = build("grid", scene, {"res=4,4,4", mailbox});
    ASSERT_TRUE(s);
    const Ray ray = make_ray({-1.0f, 0.2f, 0.3f}, {1.0f, 0.42f, 0.3f});
    const auto got = check_grid_ray(*as_grid(s.get()), ray);
    const Hit hit = s->intersect(ray);
    EXPECT_EQ(hit.prim, 2);
    EXPECT_NEAR(hit.t, 3.5f, 1e-5f);
    ASSERT_FALSE(got.empty());
    EXPECT_EQ(got.back().cell[0], 2);  // x = 2.5 lies in the third column
  }
}

TEST(StepVarsGrid, RandomRaysMatchTheIndependentWalk) {
  const Scene scene = make_procedural_scene("cornell").value();
  auto s = build("grid", scene, {"res=7,5,6"});
  ASSERT_TRUE(s);
  for (const Ray& ray : random_rays(scene.bounds(), 40, 7)) check_grid_ray(*as_grid(s.get()), ray);
}

TEST(StepVarsGrid, VarsAtShowsTheCurrentCells) {
  const Scene scene = grid_scene();
  auto s = build("grid", scene, {"res=4,4,4"});
  ASSERT_TRUE(s);
  TraceRecorder rec;
  s->intersect_traced(make_ray({-1.0f, 0.2f, 0.3f}, {1.0f, 0.42f, 0.3f}), rec);
  const auto& ev = rec.events();
  const GridData& g = as_grid(s.get())->data();
  size_t cells = 0;
  for (size_t step = 0; step < ev.size(); ++step) {
    const StepVars* v = vars_at(ev, rec.recorded_vars(), step);
    const size_t cell = last_of(ev, step, TraceEventKind::EnterCell);
    ASSERT_LT(cell, ev.size());  // the walk starts with one
    ASSERT_NE(v, nullptr) << "step " << step;
    const auto& dda = std::get<GridDdaVars>(*v);
    EXPECT_EQ(ev[cell].node, NodeId(dda.cell[0] + g.res[0] * (dda.cell[1] + g.res[1] * dda.cell[2])))
        << "step " << step;
    cells += ev[step].kind == TraceEventKind::EnterCell;
  }
  EXPECT_EQ(cells, 5u);
}

// =======================================================================================
// kd-tree: t_split, the near child, the case and the early exit

/// Checks every KdSplitVars / KdExitVars of `ray` against the node views; `out` receives
/// them in order.
void check_kd_ray(const KdTree& kd, const Ray& ray, std::vector<StepVars>* out_vars) {
  std::vector<StepVars>& out = *out_vars;
  TraceRecorder rec;
  const Hit hit = kd.intersect_traced(ray, rec);
  const Hit fast = fast_hit(kd, ray);
  EXPECT_EQ(fast.prim, hit.prim);
  EXPECT_EQ(fast.t, hit.t);
  const auto& ev = rec.events();
  for (const RecordedVars& r : rec.recorded_vars()) {
    out.push_back(r.vars);
    const TraceEvent& e = ev[r.event];
    ASSERT_LT(r.event + 1, ev.size()) << "something always follows";
    const TraceEvent& next = ev[r.event + 1];
    if (const auto* v = std::get_if<KdSplitVars>(&r.vars)) {
      ASSERT_EQ(e.kind, TraceEventKind::Visit);
      const NodeView node = kd.node_view(e.node);
      ASSERT_FALSE(node.leaf);
      EXPECT_EQ(v->axis, node.split_axis);
      EXPECT_EQ(v->t_min, e.t0);
      EXPECT_EQ(v->t_max, e.t1);
      const int a = node.split_axis;
      const double t_split = (double(node.split_pos) - double(ray.org[a])) / double(ray.dir[a]);
      if (std::isnan(t_split))
        EXPECT_TRUE(std::isnan(v->t_split));
      else
        EXPECT_TRUE(near_rel(v->t_split, t_split, 4e-7)) << "t_split of node " << e.node;
      const std::vector<NodeId> kids = kd.node_children(e.node);  // below, above
      ASSERT_EQ(kids.size(), 2u);
      const bool below_near = !std::signbit(ray.dir[a]);
      EXPECT_EQ(v->near_child, below_near ? kids[0] : kids[1]);
      EXPECT_EQ(v->far_child, below_near ? kids[1] : kids[0]);
      switch (v->kase) {
        case KdCase::NearOnly:
          EXPECT_GT(v->t_split, v->t_max);
          EXPECT_EQ(next.kind, TraceEventKind::Cull);
          EXPECT_EQ(next.node, v->far_child);
          break;
        case KdCase::FarOnly:
          EXPECT_LT(v->t_split, v->t_min);
          EXPECT_EQ(next.kind, TraceEventKind::Cull);
          EXPECT_EQ(next.node, v->near_child);
          break;
        case KdCase::Both:
          if (!std::isnan(v->t_split)) {
            EXPECT_TRUE(v->t_split >= v->t_min || near_rel(v->t_split, v->t_min, 1e-6));
            EXPECT_TRUE(v->t_split <= v->t_max || near_rel(v->t_split, v->t_max, 1e-6));
          }
          EXPECT_EQ(next.kind, TraceEventKind::Push);
          EXPECT_EQ(next.node, v->far_child);
          break;
      }
    } else if (const auto* x = std::get_if<KdExitVars>(&r.vars)) {
      ASSERT_EQ(e.kind, TraceEventKind::Pop);
      EXPECT_EQ(e.node, x->far_child);
      EXPECT_EQ(e.t0, x->t_split);
      EXPECT_EQ(x->t_hit, closest_after(ev, r.event, ray.tmax));
      // The lecture's "t_hit < t_split"; within rounding of t_split the traversal keeps the far
      // child (kd_lower: a visit too many, never a triangle lost), e.g. a wall in a split plane.
      if (near_rel(x->t_hit, x->t_split, 1e-6))
        EXPECT_TRUE(!x->exits || x->t_hit < x->t_split);
      else
        EXPECT_EQ(x->exits, x->t_hit < x->t_split);
      EXPECT_EQ(next.kind, x->exits ? TraceEventKind::Cull : TraceEventKind::Visit);
      EXPECT_EQ(next.node, x->far_child);
    } else {
      ADD_FAILURE() << "a kd-tree records only KdSplitVars and KdExitVars";
    }
  }
}

std::vector<StepVars> kd_vars(const KdTree& kd, const Ray& ray) {
  std::vector<StepVars> vars;
  check_kd_ray(kd, ray, &vars);
  return vars;
}

/// Triangle 0 in the plane x = 0.5, triangle 1 in x = 5.5 (larger): the root box is
/// [0.5, 5.5] x [-2, 2]^2, x its longest axis, so the middle split cuts x = 3.
Scene kd_scene() {
  std::vector<Vec3> p = {{0.5f, -1, -1}, {0.5f, 1, -1}, {0.5f, 0, 1}, {5.5f, -2, -2}, {5.5f, 2, -2}, {5.5f, 0, 2}};
  return Scene(std::move(p), {{0, 1, 2}, {3, 4, 5}}, "kd_vars");
}

TEST(StepVarsKd, HandCheckedTreeAndCases) {
  const Scene scene = kd_scene();
  auto s = build("kdtree", scene, {"split=middle", "axis=longest"});
  ASSERT_TRUE(s);
  const auto* kd = dynamic_cast<const KdTree*>(s.get());
  ASSERT_NE(kd, nullptr);
  // The known tree: root split x = 3, below leaf {0} (node 1), above leaf {1} (node 2).
  ASSERT_EQ(kd->data().nodes.size(), 3u);
  const NodeView root = kd->node_view(0);
  ASSERT_FALSE(root.leaf);
  ASSERT_EQ(root.split_axis, 0);
  ASSERT_EQ(root.split_pos, 3.0f);
  ASSERT_EQ(kd->node_prims(1), std::vector<uint32_t>{0});
  ASSERT_EQ(kd->node_prims(2), std::vector<uint32_t>{1});

  struct Expect {
    const char* what;
    Ray ray;
    int prim;
    std::vector<KdCase> cases;  // the KdSplitVars in order
    std::vector<bool> exits;    // the KdExitVars in order
    float t_split;
  };
  const std::vector<Expect> cases = {
      {"+x through both: (a), the hit before t_split ends it", make_ray({-1, 0, 0}, {1, 0, 0}), 0, {KdCase::Both},
       {true}, 4.0f},
      {"-x: the above child is near", make_ray({6.5f, 0, 0}, {-1, 0, 0}), 1, {KdCase::Both}, {true}, 3.5f},
      {"tmax before the plane: (b)", make_ray({-1, 0, 0}, {1, 0, 0}, 0.0f, 3.0f), 0, {KdCase::NearOnly}, {}, 4.0f},
      {"tmin beyond the plane: (c)", make_ray({-1, 0, 0}, {1, 0, 0}, 4.5f), 1, {KdCase::FarOnly}, {}, 4.0f},
      {"misses the near triangle: no exit", make_ray({-1, 0.8f, 0}, {1, 0, 0}), 1, {KdCase::Both}, {false}, 4.0f},
  };
  for (const Expect& c : cases) {
    SCOPED_TRACE(c.what);
    const auto vars = kd_vars(*kd, c.ray);
    std::vector<KdCase> got_cases;
    std::vector<bool> got_exits;
    for (const StepVars& v : vars) {
      if (const auto* sv = std::get_if<KdSplitVars>(&v)) {
        got_cases.push_back(sv->kase);
        EXPECT_FLOAT_EQ(sv->t_split, c.t_split);
        EXPECT_EQ(sv->near_child, c.ray.dir.x > 0 ? 1u : 2u);
      }
      if (const auto* xv = std::get_if<KdExitVars>(&v)) got_exits.push_back(xv->exits);
    }
    EXPECT_EQ(got_cases, c.cases);
    EXPECT_EQ(got_exits, c.exits);
    EXPECT_EQ(s->intersect(c.ray).prim, c.prim);
  }
  // The first ray's interval, by hand: enters the root at x = 0.5 (t = 1.5), leaves at 5.5.
  const auto vars = kd_vars(*kd, cases[0].ray);
  ASSERT_EQ(vars.size(), 2u);
  const auto& first = std::get<KdSplitVars>(vars[0]);
  EXPECT_FLOAT_EQ(first.t_min, 1.5f);
  EXPECT_NEAR(first.t_max, 6.5f, 1e-5f);
  const auto& exit = std::get<KdExitVars>(vars[1]);
  EXPECT_FLOAT_EQ(exit.t_hit, 1.5f);
  EXPECT_FLOAT_EQ(exit.t_split, 4.0f);
  EXPECT_EQ(exit.far_child, 2u);
}

TEST(StepVarsKd, RandomRaysOnSahTrees) {
  for (const char* name : {"cornell", "sphere"}) {
    const Scene scene = make_procedural_scene(name).value();
    auto s = build("kdtree", scene, {});
    ASSERT_TRUE(s);
    size_t split_vars = 0, exit_vars = 0;
    for (const Ray& ray : random_rays(scene.bounds(), 40, 11)) {
      for (const StepVars& v : kd_vars(*dynamic_cast<const KdTree*>(s.get()), ray)) {
        split_vars += std::holds_alternative<KdSplitVars>(v);
        exit_vars += std::holds_alternative<KdExitVars>(v);
      }
    }
    EXPECT_GT(split_vars, 40u) << name;
    EXPECT_GT(exit_vars, 0u) << name;
  }
}

// =======================================================================================
// Octree: the children's order, distances and fates

void check_octree_ray(const Octree& oct, const Ray& ray, size_t* checked_children) {
  TraceRecorder rec;
  const Hit hit = oct.intersect_traced(ray, rec);
  const Hit fast = fast_hit(oct, ray);
  EXPECT_EQ(fast.prim, hit.prim);
  EXPECT_EQ(fast.t, hit.t);
  const auto& ev = rec.events();
  const unsigned mask = unsigned(std::signbit(ray.dir.x)) | unsigned(std::signbit(ray.dir.y)) << 1 |
                        unsigned(std::signbit(ray.dir.z)) << 2;
  for (const RecordedVars& r : rec.recorded_vars()) {
    const auto* v = std::get_if<OctreeOrderVars>(&r.vars);
    ASSERT_NE(v, nullptr) << "an octree records only OctreeOrderVars";
    EXPECT_EQ(v->mask, mask);
    ASSERT_EQ(v->count, 8);
    const size_t visit = last_of(ev, r.event, TraceEventKind::Visit);
    ASSERT_LT(visit, ev.size());
    const NodeId parent = ev[visit].node;
    const std::vector<NodeId> kids = oct.node_children(parent);
    ASSERT_EQ(kids.size(), 8u);
    const float closest = closest_after(ev, r.event, ray.tmax);
    // The pushes that follow the vars, up to the next pop.
    std::map<NodeId, float> pushed;
    for (size_t i = r.event + 1; i < ev.size() && ev[i].kind == TraceEventKind::Push; ++i) pushed[ev[i].node] = ev[i].t0;
    size_t n_pushed = 0;
    for (unsigned i = 0; i < 8; ++i) {
      const OctreeOrderVars::Child& c = v->children[i];
      EXPECT_EQ(c.octant, i ^ mask);
      EXPECT_EQ(c.node, kids[i ^ mask]);
      const NodeView view = oct.node_view(c.node);
      EXPECT_EQ(view.depth, oct.node_view(parent).depth + 1);
      double t0 = 0, t1 = 0;
      const bool hits = slab(ray, view.box, &t0, &t1);
      const double scale = 1e-5 * std::max(1.0, std::abs(t0));
      switch (c.fate) {
        case OctreeOrderVars::Fate::Empty:
          EXPECT_TRUE(view.leaf && view.prim_count == 0) << c.node;
          break;
        case OctreeOrderVars::Fate::Missed:
          EXPECT_TRUE(!hits || t1 - t0 <= scale) << "child " << c.node << " [" << t0 << ", " << t1 << "]";
          EXPECT_FALSE(pushed.count(c.node));
          break;
        case OctreeOrderVars::Fate::BeyondClosestHit:
          EXPECT_GT(c.t_enter, closest);
          EXPECT_TRUE(near_rel(c.t_enter, t0, 1e-5)) << c.node;
          EXPECT_FALSE(pushed.count(c.node));
          break;
        case OctreeOrderVars::Fate::Pushed:
          ++n_pushed;
          ++*checked_children;
          EXPECT_TRUE(hits || t0 - t1 <= scale) << "child " << c.node;
          EXPECT_TRUE(near_rel(c.t_enter, t0, 1e-5)) << "t_enter of child " << c.node;
          EXPECT_TRUE(near_rel(c.t_exit, t1, 1e-5)) << "t_exit of child " << c.node;
          EXPECT_LE(c.t_enter, closest);
          ASSERT_TRUE(pushed.count(c.node)) << c.node;
          EXPECT_EQ(pushed[c.node], c.t_enter);
          break;
      }
    }
    EXPECT_EQ(n_pushed, pushed.size());
  }
}

TEST(StepVarsOctree, OrderDistancesAndFates) {
  for (const char* name : {"cornell", "sphere"}) {
    const Scene scene = make_procedural_scene(name).value();
    auto s = build("octree", scene, {});
    ASSERT_TRUE(s);
    const auto* oct = dynamic_cast<const Octree*>(s.get());
    size_t children = 0;
    std::vector<Ray> rays = random_rays(scene.bounds(), 40, 5);
    const Vec3 c = scene.bounds().center();
    rays.push_back(make_ray(c + Vec3(-5, 0.1f, 0.2f), {1, 0, 0}));  // axis-aligned: zero components
    rays.push_back(make_ray(c + Vec3(3, 4, 5), {-0.3f, -0.4f, -0.5f}));
    for (const Ray& ray : rays) check_octree_ray(*oct, ray, &children);
    EXPECT_GT(children, 40u) << name;
  }
}

TEST(StepVarsOctree, FixedOrderHasMaskZero) {
  const Scene scene = make_procedural_scene("cornell").value();
  auto s = build("octree", scene, {"order=fixed"});
  ASSERT_TRUE(s);
  TraceRecorder rec;
  s->intersect_traced(make_ray({2, 1.5f, 3}, {-0.5f, -0.2f, -1}), rec);
  ASSERT_FALSE(rec.recorded_vars().empty());
  for (const RecordedVars& r : rec.recorded_vars()) {
    const auto& v = std::get<OctreeOrderVars>(r.vars);
    EXPECT_EQ(v.mask, 0u);
    for (unsigned i = 0; i < 8; ++i) EXPECT_EQ(v.children[i].octant, i);
  }
}

// =======================================================================================
// Hierarchies: no vars; the pending keys are the volumes' entry distances

/// Entry distance of `ray` into sphere (c, r) clipped to tmin, in double; NaN on a miss.
double sphere_entry(const Ray& ray, const BoundingSphere& s, double r) {
  const DVec3 oc = DVec3(ray.org) - DVec3(s.center), d(ray.dir);
  const double a = glm::dot(d, d), t_mid = -glm::dot(oc, d) / a;
  const DVec3 p = oc + t_mid * d;
  const double disc = r * r - glm::dot(p, p);
  if (disc < 0.0) return std::nan("");
  return std::max(double(ray.tmin), t_mid - std::sqrt(disc / a));
}

/// Whether `key` is the entry distance of the ray into node `id`'s volume: the box's by the
/// slab test, the sphere's between the entries into slightly larger and smaller spheres
/// (the structure widens its spheres by a few ulps; grazing rays make the entry sensitive).
::testing::AssertionResult key_is_entry(const Structure& s, const Ray& ray, NodeId id, float key) {
  const NodeView v = s.node_view(id);
  if (!v.sphere.empty()) {
    const double r = v.sphere.radius;
    const double early = sphere_entry(ray, v.sphere, r * (1 + 1e-5));
    double late = sphere_entry(ray, v.sphere, r * (1 - 1e-5));
    if (std::isnan(late)) {  // grazing: the entry may be as late as the closest approach
      const DVec3 oc = DVec3(ray.org) - DVec3(v.sphere.center), d(ray.dir);
      late = std::max(double(ray.tmin), -glm::dot(oc, d) / glm::dot(d, d));
    }
    const double tol = 1e-6 * std::max(1.0, std::abs(early));
    if (!std::isnan(early) && key >= early - tol && key <= late + tol) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "node " << id << " key " << key << " not in [" << early << ", " << late
                                         << "]";
  }
  double t0, t1;
  if (!slab(ray, v.box, &t0, &t1) && t0 - t1 > 1e-5 * std::max(1.0, std::abs(t0)))
    return ::testing::AssertionFailure() << "node " << id << " pending but its box is missed";
  if (near_rel(key, t0, 1e-5)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "node " << id << " key " << key << ", box entry " << t0;
}

void check_hierarchy(const Structure& s, const std::vector<Ray>& rays, size_t* checked_keys) {
  for (const Ray& ray : rays) {
    TraceRecorder rec;
    const Hit hit = s.intersect_traced(ray, rec);
    const Hit fast = s.intersect(ray);
    EXPECT_EQ(fast.prim, hit.prim);
    EXPECT_EQ(fast.t, hit.t);
    EXPECT_TRUE(rec.recorded_vars().empty()) << "hierarchies record no vars";
    const auto& ev = rec.events();
    for (size_t step = 0; step < ev.size(); ++step) {
      const TraceHighlight h = trace_highlight(ev, step);
      EXPECT_EQ(h.closest_t, closest_after(ev, step)) << "step " << step;
      for (const PendingNode& p : h.pending) {
        EXPECT_TRUE(key_is_entry(s, ray, p.node, p.key)) << "step " << step;
        ++*checked_keys;
      }
    }
    const TraceHighlight end = trace_highlight(ev, ev.size() - 1);
    EXPECT_EQ(end.closest_prim, hit.prim);
    EXPECT_EQ(end.closest_t, hit.t);
  }
}

TEST(StepVarsHierarchy, PendingKeysAreEntryDistances) {
  const Scene scene = make_procedural_scene("cornell").value();
  std::vector<Ray> rays = random_rays(scene.bounds(), 12, 3);
  rays.push_back(make_ray({0.1f, 1.0f, 3.0f}, {0.05f, -0.1f, -1.0f}));
  const std::vector<std::pair<std::string, std::vector<std::string>>> configs = {
      {"bvh", {"width=2", "traversal=pqueue"}},       {"bvh", {"width=2", "traversal=ordered"}},
      {"bvh", {"width=4", "traversal=pqueue"}},       {"bvh", {"width=4", "traversal=ordered"}},
      {"spheretree", {"traversal=pqueue"}},           {"spheretree", {"traversal=ordered"}},
  };
  for (const auto& [name, params] : configs) {
    std::string what = name;
    for (const std::string& p : params) what += " " + p;
    SCOPED_TRACE(what);
    auto s = build(name, scene, params);
    ASSERT_TRUE(s);
    size_t keys = 0;
    check_hierarchy(*s, rays, &keys);
    EXPECT_GT(keys, 20u);
  }
}

// =======================================================================================
// Recording changes nothing

TEST(StepVars, RecordingChangesNoAnswer) {
  const Scene scene = make_procedural_scene("cornell").value();
  const std::vector<Ray> rays = random_rays(scene.bounds(), 50, 17);
  const std::vector<std::pair<std::string, std::vector<std::string>>> configs = {
      {"brute", {}}, {"grid", {}}, {"grid", {"mailbox=off"}}, {"octree", {}}, {"octree", {"order=fixed"}},
      {"kdtree", {}}, {"bvh", {"width=2"}}, {"bvh", {}}, {"spheretree", {}}};
  for (const auto& [name, params] : configs) {
    auto s = build(name, scene, params);
    ASSERT_TRUE(s);
    for (const Ray& ray : rays) {
      TraceRecorder rec;
      QueryStats stats;
      const Hit traced = s->intersect_traced(ray, rec);
      const Hit fast = s->intersect(ray);
      const Hit counted = s->intersect(ray, &stats);
      EXPECT_EQ(traced.prim, fast.prim) << name;
      EXPECT_EQ(traced.t, fast.t) << name;
      EXPECT_EQ(counted.prim, fast.prim) << name;
      EXPECT_EQ(counted.t, fast.t) << name;
    }
  }
}

// =======================================================================================
// node_children: the tree's shape

TEST(NodeChildren, EveryNodeReachedOnceFromTheRoot) {
  const Scene scene = make_procedural_scene("sphere").value();
  const std::vector<std::pair<std::string, std::vector<std::string>>> configs = {
      {"bvh", {"width=2"}}, {"bvh", {"width=4"}}, {"bvh", {"width=8"}},
      {"spheretree", {}},   {"kdtree", {}},       {"octree", {}}};
  for (const auto& [name, params] : configs) {
    SCOPED_TRACE(name + (params.empty() ? "" : " " + params[0]));
    auto s = build(name, scene, params);
    ASSERT_TRUE(s);
    size_t nodes = 0;
    s->for_each_node([&](const NodeView&) { ++nodes; });
    ASSERT_GT(nodes, 1u);
    std::vector<int> reached(nodes, 0);
    std::vector<NodeId> todo{0};
    reached[0] = 1;
    size_t inner = 0;
    while (!todo.empty()) {
      const NodeId id = todo.back();
      todo.pop_back();
      const NodeView v = s->node_view(id);
      const std::vector<NodeId> kids = s->node_children(id);
      if (v.leaf) {
        EXPECT_TRUE(kids.empty()) << "leaf " << id;
        continue;
      }
      ++inner;
      EXPECT_FALSE(kids.empty()) << "inner node " << id;
      EXPECT_TRUE(s->node_prims(id).empty()) << "inner node " << id;
      for (NodeId c : kids) {
        ASSERT_LT(c, nodes);
        EXPECT_EQ(s->node_view(c).depth, v.depth + 1) << id << " -> " << c;
        if (++reached[c] == 1) todo.push_back(c);
      }
    }
    EXPECT_GT(inner, 0u);
    for (size_t id = 0; id < nodes; ++id) EXPECT_EQ(reached[id], 1) << "node " << id;
    EXPECT_TRUE(s->node_children(NodeId(nodes)).empty()) << "out of range";
  }
}

TEST(NodeChildren, GridAndBruteForceHaveNone) {
  const Scene scene = make_procedural_scene("sphere").value();
  for (const char* name : {"grid", "brute"}) {
    auto s = build(name, scene, {});
    ASSERT_TRUE(s);
    size_t checked = 0;
    s->for_each_node([&](const NodeView& v) {
      EXPECT_TRUE(s->node_children(v.id).empty()) << name << " " << v.id;
      ++checked;
    });
    EXPECT_GT(checked, 0u) << name;
    EXPECT_TRUE(s->node_children(0).empty()) << name;
  }
}

// =======================================================================================
// describe_vars

TEST(DescribeVars, GridNamesAsInTheLecture) {
  GridDdaVars v;
  v.cell[0] = 3;
  v.cell[1] = 0;
  v.cell[2] = 1;
  v.step[0] = 1;
  v.step[1] = -1;
  v.step[2] = 0;
  v.t_max[0] = 0.5f;
  v.t_max[1] = 0.75f;
  v.t_max[2] = kInf;
  v.t_delta[0] = 0.25f;
  v.t_delta[1] = 2.0f;
  v.t_delta[2] = 0.0f;
  v.next_axis = 0;
  // Whole space-separated tokens: "Y=0" must not match inside "tMaxY=0.75".
  const std::string s = describe_vars(v);
  std::istringstream in(s);
  std::vector<std::string> tokens{std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
  for (const char* part : {"X=3", "Y=0", "Z=1", "stepX=1", "stepY=-1", "stepZ=0", "tMaxX=0.5", "tMaxY=0.75",
                           "tMaxZ=inf", "tDeltaX=0.25", "tDeltaY=2", "tDeltaZ=0", "next=x"})
    EXPECT_NE(std::find(tokens.begin(), tokens.end(), part), tokens.end()) << part << " in: " << s;
}

TEST(DescribeVars, KdSplitNamesTheCase) {
  const KdSplitVars a{0.5f, 2.5f, 4.0f, 1, 7, 0, KdCase::Both};
  const std::string sa = describe_vars(a);
  EXPECT_NE(sa.find("t_split=2.5"), std::string::npos) << sa;
  EXPECT_NE(sa.find("case=a(both)"), std::string::npos) << sa;
  const KdSplitVars b{0.5f, 5.0f, 4.0f, 1, 7, 0, KdCase::NearOnly};
  EXPECT_NE(describe_vars(b).find("case=b(near_only)"), std::string::npos) << describe_vars(b);
  const KdSplitVars c{0.5f, 0.25f, 4.0f, 1, 7, 0, KdCase::FarOnly};
  EXPECT_NE(describe_vars(c).find("case=c(far_only)"), std::string::npos) << describe_vars(c);
}

}  // namespace
}  // namespace accel
