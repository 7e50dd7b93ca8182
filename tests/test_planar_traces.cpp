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

}  // namespace
}  // namespace accel
