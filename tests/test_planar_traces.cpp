// Hand-checked 2D traversals (issue #32): each structure built by its own builder over a 2D
// scene of a few triangles, the 2D ray's events checked step by step, as the 3D tests do.
#include <gtest/gtest.h>

#include "registry.h"
#include "scene2d.h"
#include "structures/octree.h"
#include "test_support.h"

namespace accel {
namespace {

using testing::trace_tokens;

Ray ray2d(float ox, float oy, float dx, float dy) {
  Ray r;
  r.org = Vec3(ox, oy, 0.0f);
  r.dir = Vec3(dx, dy, 0.0f);
  return r;
}

std::unique_ptr<Structure> build(const Scene& scene, const std::string& name, const std::vector<std::string>& params) {
  auto built = build_structure(name, scene, params);
  EXPECT_TRUE(built) << built.error().message;
  return built ? std::move(built.value()) : nullptr;
}

// [SECTION] Quadtree (the octree over a 2D scene)
//
// The root is the square [0,4]^2 (T0 touches (0,0), T1 (4,4)), split once at (2,2)
// (max_prims = 1, ct = 0: 4 triangles, 4 references, 0 + 4/2 < 4). Children ids 1 + octant,
// bit x = 1, y = 2: id 1 (x lo y lo) T0, id 2 (x hi y lo) T2, id 3 (x lo y hi) T3, id 4
// (x hi y hi) T1; ids 5..8, the upper-z octants, stay empty.
// Ray Q from (3.75, 0) along (-1, 1) runs on x + y = 3.75: through id 2 (t in [0, 1.75]),
// id 1 ([1.75, 2]) and id 3 (from t = 2), never id 4 (x + y > 4 there). It enters T2 (whose
// long edge is x + y = 4) through its bottom edge y = 0.5 at t = 0.5.
const char* kQuadScene =
    "tri 0 0 1 0 0 1\n"              // T0
    "tri 4 4 3 4 4 3\n"              // T1
    "tri 2.5 0.5 3.5 0.5 2.5 1.5\n"  // T2
    "tri 0.5 2.5 1.5 2.5 0.5 3.5\n"; // T3

TEST(QuadtreeTrace, ASquareRootSplitInFour) {
  const Scene scene = parse_scene2d(kQuadScene, "quad").value();
  auto s = build(scene, "octree", {"max_prims=1", "ct=0"});
  ASSERT_TRUE(s);
  const OctreeData& data = static_cast<const Octree&>(*s).data();
  EXPECT_TRUE(data.planar);
  EXPECT_EQ(data.root_box.min, Vec3(0.0f));
  EXPECT_EQ(data.root_box.max, Vec3(4.0f, 4.0f, 0.0f));
  EXPECT_EQ(s->node_children(0), (std::vector<NodeId>{1, 2, 3, 4}));
  const std::vector<std::vector<uint32_t>> prims = {{0}, {2}, {3}, {1}};
  for (unsigned quadrant = 0; quadrant < 4; ++quadrant) {
    const NodeView v = s->node_view(1 + quadrant);
    EXPECT_EQ(s->node_prims(1 + quadrant), prims[quadrant]) << quadrant;
    EXPECT_EQ(v.box.min, Vec3(quadrant & 1 ? 2.0f : 0.0f, quadrant & 2 ? 2.0f : 0.0f, 0.0f));
    EXPECT_EQ(v.box.max, v.box.min + Vec3(2.0f, 2.0f, 0.0f));
  }
  for (NodeId upper = 5; upper <= 8; ++upper) EXPECT_TRUE(s->node_prims(upper).empty());
  size_t drawn = 0;
  s->for_each_node([&](const NodeView&) { ++drawn; });
  EXPECT_EQ(drawn, 5u);  // the root and its four quadrants
  EXPECT_EQ(s->build_stats().prim_references, 4u);
}

TEST(QuadtreeTrace, SortedOrderVisitsQuadrantsFrontToBack) {
  const Scene scene = parse_scene2d(kQuadScene, "quad").value();
  auto s = build(scene, "octree", {"max_prims=1", "ct=0", "order=sorted"});
  ASSERT_TRUE(s);
  TraceRecorder rec;
  const Hit h = s->intersect_traced(ray2d(3.75f, 0.0f, -1.0f, 1.0f), rec);
  EXPECT_EQ(h.prim, 2);
  EXPECT_EQ(h.t, 0.5f);
  // The ray travels down x: mask 1, quadrants tested 1, 0, 3, 2 (ids 2, 1, 4, 3); the two
  // it passes after id 2 start beyond the hit at 0.5 and are culled when popped.
  const std::vector<std::string> expected = {
      "push 0", "pop 0", "visit 0",
      "cull 4 missed", "push 3", "push 1", "push 2",
      "pop 2", "visit 2", "test 2 hit", "closest 2",
      "pop 1", "cull 1 beyond",
      "pop 3", "cull 3 beyond",
      "done 2"};
  EXPECT_EQ(trace_tokens(rec), expected);
}

TEST(QuadtreeTrace, FixedOrderVisitsQuadrantsZeroToThree) {
  const Scene scene = parse_scene2d(kQuadScene, "quad").value();
  auto s = build(scene, "octree", {"max_prims=1", "ct=0", "order=fixed"});
  ASSERT_TRUE(s);
  TraceRecorder rec;
  EXPECT_EQ(s->intersect_traced(ray2d(3.75f, 0.0f, -1.0f, 1.0f), rec).prim, 2);
  // The lecture's unsorted order: quadrant 0 (id 1) first although the ray reaches it second.
  const std::vector<std::string> expected = {
      "push 0", "pop 0", "visit 0",
      "cull 4 missed", "push 3", "push 2", "push 1",
      "pop 1", "visit 1", "test 0 miss",
      "pop 2", "visit 2", "test 2 hit", "closest 2",
      "pop 3", "cull 3 beyond",
      "done 2"};
  EXPECT_EQ(trace_tokens(rec), expected);
}

// [SECTION] Grid, kd-tree, BVH and circle tree on the same four triangles and ray Q

// Grid 2 x 2 x 1 (res given): cell id = X + 2 Y, T0 in cell 0, T2 in 1, T3 in 2, T1 in 3. Ray
// Q starts in cell 1 (X = 1, Y = 0) and would leave it at x = 2 (t = 1.75) before y = 2
// (t = 2); T2's hit at 0.5 lies inside the cell, so the 2D DDA stops there.
TEST(PlanarGridTrace, TheDdaStopsInTheFirstCellWhoseHitLiesInside) {
  const Scene scene = parse_scene2d(kQuadScene, "quad").value();
  auto s = build(scene, "grid", {"res=2,2,1"});
  ASSERT_TRUE(s);
  EXPECT_EQ(s->node_prims(1), (std::vector<uint32_t>{2}));
  TraceRecorder rec;
  EXPECT_EQ(s->intersect_traced(ray2d(3.75f, 0.0f, -1.0f, 1.0f), rec).prim, 2);
  EXPECT_EQ(trace_tokens(rec), (std::vector<std::string>{"enter 1", "test 2 hit", "closest 2", "done 2"}));
}

// kd-tree, split=middle, round robin: the root splits x = 2, its children y = 2. Pre-order:
// 0 (x = 2), 1 (x <= 2; y = 2) with leaves 2 (T0) and 3 (T3), 4 (x >= 2; y = 2) with leaves 5
// (T2) and 6 (T1). Ray Q in the root: t in [0, 3.75], t_split = 1.75: case (a), the near
// child 4 (x >= 2, where it starts) first, the far child 1 pushed. In node 4 the plane y = 2
// lies at t = 2 > t_max = 1.75: case (b), the near child 5 only (6 is never entered). T2 is
// hit at 0.5, and node 1, entered at 1.75, is culled when popped.
TEST(PlanarKdTrace, CasesAAndBOnSplitLines) {
  const Scene scene = parse_scene2d(kQuadScene, "quad").value();
  auto s = build(scene, "kdtree", {"split=middle", "axis=round_robin", "leaf_size=1"});
  ASSERT_TRUE(s);
  EXPECT_EQ(s->node_prims(5), (std::vector<uint32_t>{2}));
  EXPECT_EQ(s->node_view(4).box.min, Vec3(2.0f, 0.0f, 0.0f));
  TraceRecorder rec;
  EXPECT_EQ(s->intersect_traced(ray2d(3.75f, 0.0f, -1.0f, 1.0f), rec).prim, 2);
  EXPECT_EQ(trace_tokens(rec), (std::vector<std::string>{"visit 0", "push 1", "visit 4", "cull 6 missed", "visit 5",
                                                         "test 2 hit", "closest 2", "pop 1", "cull 1 beyond",
                                                         "done 2"}));
}

// BVH of rectangles (binary, median split, round robin): x first splits the centroids into
// {T0, T3} (node 1, box [0,1.5] x [0,3.5]) and {T2, T1} (node 4, [2.5,4] x [0.5,4]), then y
// into leaves 2 (T0), 3 (T3), 5 (T2), 6 (T1). Ray Q enters node 4 at t = 0.5 and node 1 at
// t = 2.25: the ordered traversal pushes 1, then the nearer 4 on top. In node 4, T1's box
// [3,4]^2 lies beyond the line x + y = 3.75 (missed); T2 is hit at 0.5; node 1 is culled.
// The circle tree (the sphere tree in 2D) builds the same nodes and takes the same steps:
// its circle around T1 misses the line too.
TEST(PlanarHierarchyTrace, NearerRectangleOrCircleFirst) {
  const Scene scene = parse_scene2d(kQuadScene, "quad").value();
  for (const char* name : {"bvh", "spheretree"}) {
    SCOPED_TRACE(name);
    std::vector<std::string> params = {"builder=median", "axis=round_robin", "leaf_size=1"};
    if (std::string(name) == "bvh") params.push_back("width=2");
    auto s = build(scene, name, params);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->node_view(1).box.max, Vec3(1.5f, 3.5f, 0.0f));
    EXPECT_EQ(s->node_prims(5), (std::vector<uint32_t>{2}));
    TraceRecorder rec;
    EXPECT_EQ(s->intersect_traced(ray2d(3.75f, 0.0f, -1.0f, 1.0f), rec).prim, 2);
    EXPECT_EQ(trace_tokens(rec),
              (std::vector<std::string>{"push 0", "pop 0", "visit 0", "push 1", "push 4", "pop 4", "visit 4",
                                        "cull 6 missed", "push 5", "pop 5", "visit 5", "test 2 hit", "closest 2",
                                        "pop 1", "cull 1 beyond", "done 2"}));
  }
}

// [SECTION] The octree's 2D defaults (issue #50)
//
// With the 3D defaults (max_prims=8, ct=2) no split of the blackboard's ten triangles pays
// (3 ct + refs / 2 >= 10): the root stays one no-gain leaf. Over a 2D scene the octree's
// defaults are the lecture's quadtree's (max_prims=1, ct=0), so the lecture's board is
// subdivided without parameters; explicit ones still win, and the 3D defaults are unchanged.
TEST(QuadtreeDefaults, TheBlackboardIsSubdividedWithoutParameters) {
  auto scene = load_scene2d(std::string(ACCEL_SOURCE_DIR) + "/scenes/blackboard.scene2d");
  ASSERT_TRUE(scene) << scene.error().message;
  ASSERT_TRUE(scene.value().planar());
  ASSERT_EQ(scene.value().triangle_count(), 10u);
  auto s = build(scene.value(), "octree", {});
  ASSERT_TRUE(s);
  const BuildStats st = s->build_stats();
  EXPECT_GT(st.leaves, 1u);
  EXPECT_GT(st.max_depth, 1);
  EXPECT_GT(static_cast<const Octree&>(*s).data().reasons.few_prims, 1u);  // cells of at most one triangle
  // The same tree as with the lecture's stop written out.
  auto lecture = build(scene.value(), "octree", {"max_prims=1", "ct=0"});
  ASSERT_TRUE(lecture);
  EXPECT_EQ(lecture->build_stats().nodes, st.nodes);
  EXPECT_EQ(lecture->build_stats().leaves, st.leaves);
  // The 3D defaults given explicitly: one no-gain leaf, as before.
  auto costed = build(scene.value(), "octree", {"max_prims=8", "ct=2"});
  ASSERT_TRUE(costed);
  EXPECT_EQ(costed->build_stats().leaves, 1u);
  EXPECT_EQ(static_cast<const Octree&>(*costed).data().reasons.no_gain, 1u);
  // The 3D defaults themselves are unchanged.
  for (const ParamSpec& spec : Octree::param_specs()) {
    if (spec.name == "max_prims") {
      EXPECT_EQ(spec.default_value, "8");
      ASSERT_TRUE(spec.planar_default);
      EXPECT_EQ(std::get<int>(*spec.planar_default), 1);
    } else if (spec.name == "ct") {
      EXPECT_EQ(spec.default_value, "2");
      ASSERT_TRUE(spec.planar_default);
      EXPECT_EQ(std::get<double>(*spec.planar_default), 0.0);
    } else {
      EXPECT_FALSE(spec.planar_default) << spec.name;
    }
  }
}

}  // namespace
}  // namespace accel
