// AABB tree (bvh): every builder x traversal x leaf size against the reference, hand-checked
// traversal orders, tree validity, and SAH quality of the sweep vs binned builders.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "structures/bvh.h"
#include "structures/bvh_builders.h"
#include "random.h"
#include "registry.h"
#include "structure_suite.h"
#include "test_support.h"

namespace accel {
namespace {

using testing::four_walls;
using testing::SuiteCase;

std::vector<SuiteCase> bvh_cases(const std::string& structure) {
  std::vector<SuiteCase> cases;
  for (const BvhBuilderInfo& row : bvh_builder_table()) {
    if (row.splits_triangles) continue;  // two configurations below (their own tests: test_bvh_spatial.cpp)
    const char* builder = row.name;
    for (const char* traversal : {"dfs", "ordered", "pqueue"})
      cases.push_back({structure, {std::string("builder=") + builder, std::string("traversal=") + traversal}});
    for (const char* leaf : {"leaf_size=1", "leaf_size=16"})
      cases.push_back({structure, {std::string("builder=") + builder, leaf}});
  }
  if (structure == "bvh") {  // every layout by name beside the default (auto: 8 wide with AVX2, else 4)
    for (const char* traversal : {"dfs", "ordered", "pqueue"}) {
      cases.push_back({structure, {"width=2", std::string("traversal=") + traversal}});
      cases.push_back({structure, {"width=4", std::string("traversal=") + traversal}});
    }
    for (const char* traversal : {"dfs", "ordered"}) cases.push_back({structure, {"width=8", std::string("traversal=") + traversal}});
    cases.push_back({structure, {"width=2", "builder=bottom_up", "leaf_size=16"}});
  }
  cases.push_back({structure, {"builder=median", "axis=x"}});
  cases.push_back({structure, {"builder=median", "axis=round_robin"}});
  cases.push_back({structure, {"builder=binned_sah", "bins=2"}});
  // Spatial splits: two configurations only (the builder's own tests: test_bvh_spatial.cpp).
  cases.push_back({structure, {"builder=sbvh", "traversal=ordered"}});
  if (structure == "bvh") cases.push_back({structure, {"width=2", "builder=sbvh", "traversal=pqueue", "leaf_size=1"}});
  cases.push_back({structure, {"builder=sah", "ct=100", "ci=0.01"}});  // extreme costs: deep tree
  return cases;
}

}  // namespace

namespace testing {
INSTANTIATE_TEST_SUITE_P(Bvh, StructureVsReference, ::testing::ValuesIn(bvh_cases("bvh")), suite_case_name);
}  // namespace testing

namespace {

struct Steps {
  std::vector<NodeId> visits, culls, pops;
  std::vector<CullReason> reasons;
  std::vector<float> pop_keys;
};

Steps record(const Structure& s, const Ray& r, Hit* hit) {
  TraceRecorder rec;
  *hit = s.intersect_traced(r, rec);
  Steps steps;
  for (const TraceEvent& e : rec.events()) {
    if (e.kind == TraceEventKind::Visit) steps.visits.push_back(e.node);
    if (e.kind == TraceEventKind::Cull) {
      steps.culls.push_back(e.node);
      steps.reasons.push_back(e.reason);
    }
    if (e.kind == TraceEventKind::Pop) {
      steps.pops.push_back(e.node);
      steps.pop_keys.push_back(e.t0);
    }
  }
  return steps;
}

/// Builds `structure`; the hand-checked binary-tree tests below use bvh's lecture layout
/// (width=2) unless `params` choose a width.
std::unique_ptr<Structure> build(const std::string& structure, const Scene& scene, std::vector<std::string> params) {
  const bool has_width = std::any_of(params.begin(), params.end(), [](const std::string& p) { return p.rfind("width=", 0) == 0; });
  if (structure == "bvh" && !has_width) params.push_back("width=2");
  auto built = build_structure(structure, scene, params);
  EXPECT_TRUE(built) << (built ? "" : built.error().message);
  return built ? std::move(built.value()) : nullptr;
}

class HierarchyOrder : public ::testing::TestWithParam<std::string> {};

TEST_P(HierarchyOrder, FourWallsTreeLayout) {
  const Scene scene = four_walls();
  auto s = build(GetParam(), scene, {"builder=median", "axis=x", "leaf_size=1"});
  ASSERT_TRUE(s);
  EXPECT_EQ(s->node_prims(2), std::vector<uint32_t>{0});
  EXPECT_EQ(s->node_prims(3), std::vector<uint32_t>{1});
  EXPECT_EQ(s->node_prims(5), std::vector<uint32_t>{2});
  EXPECT_EQ(s->node_prims(6), std::vector<uint32_t>{3});
}

TEST_P(HierarchyOrder, DfsVisitsInTreeOrder) {
  // The ray comes from +x: tree order (left = low x first) is back to front, so DFS visits
  // every node and improves the closest hit three times.
  const Scene scene = four_walls();
  auto s = build(GetParam(), scene, {"builder=median", "axis=x", "leaf_size=1", "traversal=dfs"});
  Ray r;
  r.org = Vec3(10, 0, 0);
  r.dir = Vec3(-1, 0, 0);
  Hit hit;
  const Steps steps = record(*s, r, &hit);
  EXPECT_EQ(steps.visits, (std::vector<NodeId>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(hit.prim, 3);
  EXPECT_FLOAT_EQ(hit.t, 7.0f);
}

TEST_P(HierarchyOrder, OrderedVisitsNearerChildFirstAndSkipsBeyondClosest) {
  const Scene scene = four_walls();
  auto s = build(GetParam(), scene, {"builder=median", "axis=x", "leaf_size=1", "traversal=ordered"});
  const bool boxes = GetParam() == "bvh";
  Ray r;
  r.org = Vec3(10, 0, 0);
  r.dir = Vec3(-1, 0, 0);
  Hit hit;
  const Steps steps = record(*s, r, &hit);
  // Root, then its nearer child {2,3}, then the nearer leaf (prim 3, t = 7). With boxes the
  // farther leaf (entry 8) and the left subtree (entry 9) are popped and skipped. A leaf's
  // sphere (radius ~1.1) is entered ~1.1 earlier than its box, so the sphere tree must still
  // visit leaf 5 (entry ~6.9 < 7) and only skips the left subtree.
  EXPECT_EQ(steps.visits, boxes ? (std::vector<NodeId>{0, 4, 6}) : (std::vector<NodeId>{0, 4, 6, 5}));
  EXPECT_EQ(steps.culls, boxes ? (std::vector<NodeId>{5, 1}) : (std::vector<NodeId>{1}));
  for (CullReason why : steps.reasons) EXPECT_EQ(why, CullReason::BeyondClosestHit);
  EXPECT_EQ(hit.prim, 3);
  // From the other side the nearer child is the left one.
  r.org = Vec3(-10, 0, 0);
  r.dir = Vec3(1, 0, 0);
  const Steps back = record(*s, r, &hit);
  EXPECT_EQ(back.visits, boxes ? (std::vector<NodeId>{0, 1, 2}) : (std::vector<NodeId>{0, 1, 2, 3}));
  EXPECT_EQ(hit.prim, 0);
}

TEST_P(HierarchyOrder, PriorityQueuePopsByIncreasingEntryAndSkipsTheRest) {
  const Scene scene = four_walls();
  auto s = build(GetParam(), scene, {"builder=median", "axis=x", "leaf_size=1", "traversal=pqueue"});
  const bool boxes = GetParam() == "bvh";
  Ray r;
  r.org = Vec3(10, 0, 0);
  r.dir = Vec3(-1, 0, 0);
  Hit hit;
  const Steps steps = record(*s, r, &hit);
  if (boxes) {
    // Boxes nest, so a child is never entered before its parent: keys pop in order. A child
    // sphere is fitted to its own triangles and may stick out of its parent's sphere, so the
    // sphere tree pops a child with a smaller key than its parent; skipping stays correct
    // because every sphere contains all triangles below it.
    EXPECT_TRUE(std::is_sorted(steps.pop_keys.begin(), steps.pop_keys.end()));
    EXPECT_EQ(steps.visits, (std::vector<NodeId>{0, 4, 6}));
    // Popping node 5 (entry 8 > closest 7) ends the search; node 1 (entry 9) is skipped too.
    EXPECT_EQ(steps.pops.back(), 5u);
    EXPECT_EQ(steps.culls, (std::vector<NodeId>{5, 1}));
  } else {
    EXPECT_EQ(steps.visits, (std::vector<NodeId>{0, 4, 6, 5}));
    EXPECT_EQ(steps.culls.back(), 1u);
  }
  EXPECT_EQ(hit.prim, 3);
}

TEST_P(HierarchyOrder, PriorityQueueKeepsSearchingWhenNearestVolumeHoldsNoNearestHit) {
  // The lecture's warning: a slanted wall's box is entered first (x = 0, t = 10) but the wall
  // is hit late (x = -2.25, t = 12.25); a small triangle in another leaf is hit at t = 11.
  // Prim 1 is a decoy off the ray. Median on x, leaf size 1: root {decoy | {wall, small}}.
  Scene scene({{0, -5, -5}, {-3, 5, -5}, {-3, 0, 5},                     // prim 0: wall
               {-4, 3, -0.1f}, {-4, 3.1f, -0.1f}, {-4, 3, 0.1f},         // prim 1: decoy
               {-1, -0.1f, -0.1f}, {-1, 0.1f, -0.1f}, {-1, 0, 0.1f}},    // prim 2: small
              {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}});
  auto s = build(GetParam(), scene, {"builder=median", "axis=x", "leaf_size=1", "traversal=pqueue"});
  Ray r;
  r.org = Vec3(10, 0, 0);
  r.dir = Vec3(-1, 0, 0);
  TraceRecorder rec;
  const Hit hit = s->intersect_traced(r, rec);
  EXPECT_EQ(hit.prim, 2);
  EXPECT_NEAR(hit.t, 11.0f, 1e-5f);
  std::vector<int32_t> tested;
  for (const TraceEvent& e : rec.events())
    if (e.kind == TraceEventKind::TestPrim) tested.push_back(e.prim);
  // With boxes the wall's leaf is popped first and hit, yet the search goes on to prim 2.
  if (GetParam() == "bvh") {
    EXPECT_EQ(tested, (std::vector<int32_t>{0, 2}));
  }
}

INSTANTIATE_TEST_SUITE_P(Both, HierarchyOrder, ::testing::Values("bvh", "spheretree"));

// The 4-wide layout (bvh width=4, the default). With leaf_size=1 the median tree of the four
// walls collapses to one root (node 0) whose four children are the leaves of prims 0..3
// (nodes 1..4, tree order = increasing x). The ray from +x enters them at t = 10, 9, 8, 7.

TEST(WideBvh, FourWallsCollapseToOneRootWithFourLeaves) {
  const Scene scene = four_walls();
  auto s = build("bvh", scene, {"builder=median", "axis=x", "leaf_size=1", "width=4"});
  ASSERT_TRUE(s);
  const BuildStats stats = s->build_stats();
  EXPECT_EQ(stats.nodes, 5u);
  EXPECT_EQ(stats.leaves, 4u);
  EXPECT_EQ(stats.max_depth, 1);
  for (uint32_t prim = 0; prim < 4; ++prim) {
    EXPECT_EQ(s->node_prims(prim + 1), std::vector<uint32_t>{prim});
    EXPECT_EQ(s->node_view(prim + 1).depth, 1);
  }
  EXPECT_FALSE(s->node_view(0).leaf);
}

/// The four walls as a 4-wide tree walked by `traversal`, with the ray from +x.
Steps walls_from_plus_x(const std::string& traversal, Hit* hit) {
  const Scene scene = four_walls();
  auto s = build("bvh", scene, {"builder=median", "axis=x", "leaf_size=1", "width=4", "traversal=" + traversal});
  Ray r;
  r.org = Vec3(10, 0, 0);
  r.dir = Vec3(-1, 0, 0);
  return record(*s, r, hit);
}

TEST(WideBvh, DfsDescendsInTreeOrder) {
  Hit hit;
  const Steps steps = walls_from_plus_x("dfs", &hit);
  // All four boxes are tested at the root; the first child is entered at once, the other
  // three wait on the stack (pushed last-first) and each improves the closest hit.
  EXPECT_EQ(steps.visits, (std::vector<NodeId>{0, 1, 2, 3, 4}));
  EXPECT_EQ(steps.pops, (std::vector<NodeId>{2, 3, 4}));
  EXPECT_TRUE(steps.culls.empty());
  EXPECT_EQ(hit.prim, 3);
  EXPECT_FLOAT_EQ(hit.t, 7.0f);
}

TEST(WideBvh, OrderedEntersNearestChildAndSkipsTheRest) {
  Hit hit;
  const Steps steps = walls_from_plus_x("ordered", &hit);
  EXPECT_EQ(steps.visits, (std::vector<NodeId>{0, 4}));
  EXPECT_EQ(steps.pops, (std::vector<NodeId>{3, 2, 1}));
  EXPECT_EQ(steps.pop_keys, (std::vector<float>{8, 9, 10}));
  EXPECT_EQ(steps.culls, (std::vector<NodeId>{3, 2, 1}));
  for (CullReason why : steps.reasons) EXPECT_EQ(why, CullReason::BeyondClosestHit);
  EXPECT_EQ(hit.prim, 3);
}

TEST(WideBvh, PriorityQueueStopsAtTheFirstKeyBeyondTheClosestHit) {
  Hit hit;
  const Steps steps = walls_from_plus_x("pqueue", &hit);
  EXPECT_EQ(steps.visits, (std::vector<NodeId>{0, 4}));
  EXPECT_EQ(steps.pops, (std::vector<NodeId>{0, 4, 3}));
  EXPECT_EQ(steps.culls, (std::vector<NodeId>{3, 2, 1}));
  EXPECT_EQ(hit.prim, 3);
}

TEST(WideBvh, MissedChildrenAreCulledAsMissedAtTheirParent) {
  const Scene scene = four_walls();
  auto s = build("bvh", scene, {"builder=median", "axis=x", "leaf_size=1", "width=4"});
  // A ray along z through x = 1.5 enters the root box but none of the four flat leaf boxes.
  Ray r;
  r.org = Vec3(1.5f, 0, -5);
  r.dir = Vec3(0, 0, 1);
  Hit hit;
  const Steps miss = record(*s, r, &hit);
  EXPECT_FALSE(hit.valid());
  EXPECT_EQ(miss.visits, (std::vector<NodeId>{0}));
  EXPECT_EQ(miss.culls, (std::vector<NodeId>{1, 2, 3, 4}));
  for (CullReason why : miss.reasons) EXPECT_EQ(why, CullReason::MissedBounds);
}

TEST(WideBvh, RecordedStepsCountLikeTheFastPathAndAnswerAlike) {
  // The recorder, the counters and the fast path run one traversal: same hit, same counts.
  const Scene scene = make_procedural_scene("soup").value();
  for (const char* order : {"dfs", "ordered", "pqueue"}) {
    auto s = build("bvh", scene, {"width=4", std::string("traversal=") + order});
    Rng rng(5);
    for (int i = 0; i < 2000; ++i) {
      Ray r;
      r.org = Vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
      r.dir = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      TraceRecorder rec;
      QueryStats counted;
      const Hit traced = s->intersect_traced(r, rec);
      const Hit counted_hit = s->intersect(r, &counted);
      const Hit fast = s->intersect(r);
      ASSERT_EQ(traced.prim, fast.prim) << order << " ray " << i;
      ASSERT_EQ(counted_hit.prim, fast.prim);
      ASSERT_EQ(traced.t, fast.t);
      const QueryStats replayed = rec.stats();
      EXPECT_EQ(replayed.nodes_visited, counted.nodes_visited);
      // The priority queue shows the recorder every node still queued when it stops; the
      // counters skip that loop.
      if (std::string(order) == "pqueue")
        EXPECT_GE(replayed.nodes_culled, counted.nodes_culled);
      else
        EXPECT_EQ(replayed.nodes_culled, counted.nodes_culled) << order;
      EXPECT_EQ(replayed.prims_tested, counted.prims_tested);
    }
  }
}

TEST(WideBvh, BothWidthsFindTheSameHits) {
  const Scene scene = make_procedural_scene("stadium").value();
  auto binary = build("bvh", scene, {"width=2"});
  auto wide = build("bvh", scene, {"width=4"});
  Rng rng(9);
  const Aabb box = scene.bounds();
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    Ray r;
    r.org = box.center() + box.extent() * Vec3(rng.uniform(-0.7f, 0.7f), rng.uniform(-0.7f, 0.7f), rng.uniform(-0.7f, 0.7f));
    r.dir = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Hit a = binary->intersect(r), b = wide->intersect(r);
    ASSERT_EQ(a.valid(), b.valid()) << "ray " << i;
    if (!a.valid()) continue;
    ++hits;
    // Same triangle, or a tie at the same distance (the leaves may list them in another order).
    if (a.prim != b.prim) {
      EXPECT_EQ(a.t, b.t) << "ray " << i;
    }
    EXPECT_NEAR(a.t, b.t, 1e-6f * std::max(1.0f, a.t)) << "ray " << i;
  }
  EXPECT_GT(hits, 1000);
}

/// Every triangle in exactly one leaf, leaves within leaf_size, children inside parents.
void expect_valid_tree(const BinaryBvh& bvh, const Scene& scene, int leaf_size) {
  const auto& nodes = bvh.nodes();
  std::multiset<uint32_t> seen;
  for (NodeId i = 0; i < nodes.size(); ++i) {
    const auto& n = nodes[i];
    if (n.leaf()) {
      EXPECT_LE(int(n.count), leaf_size);
      for (uint32_t prim : bvh.node_prims(i)) {
        seen.insert(prim);
        EXPECT_TRUE(n.volume.contains(scene.triangle_bounds(prim))) << "leaf " << i;
      }
    } else {
      ASSERT_LT(i + 1, nodes.size());
      ASSERT_LT(n.index, nodes.size());
      EXPECT_TRUE(n.volume.contains(nodes[i + 1].volume)) << "node " << i;
      EXPECT_TRUE(n.volume.contains(nodes[n.index].volume)) << "node " << i;
    }
  }
  EXPECT_EQ(seen.size(), scene.valid_prims().size());
  for (uint32_t prim : scene.valid_prims()) EXPECT_EQ(seen.count(prim), 1u) << "prim " << prim;
}

/// The same for the wide layouts: every triangle in exactly one leaf, within the leaf's
/// box; every child slot's box inside its node's box, and at most W children.
template <int W>
void expect_valid_wide_tree(const WideBvhOf<W>& wide, const Scene& scene, int leaf_size) {
  const Structure& bvh = wide;
  std::multiset<uint32_t> seen;
  for (NodeId i = 0; i < wide.size(); ++i) {
    const NodeView v = bvh.node_view(i);
    if (v.leaf) {
      EXPECT_LE(int(v.prim_count), leaf_size);
      for (uint32_t prim : bvh.node_prims(i)) {
        seen.insert(prim);
        EXPECT_TRUE(v.box.contains(scene.triangle_bounds(prim))) << "leaf " << i;
      }
      continue;
    }
    const WideNodeOf<W>& n = wide.wide_node(i);
    int children = 0;
    for (int slot = 0; slot < W; ++slot) {
      if (n.bounds[0][slot] > n.bounds[3][slot]) continue;  // unused slot (empty box)
      ++children;
      Aabb child;
      child.min = Vec3(n.bounds[0][slot], n.bounds[1][slot], n.bounds[2][slot]);
      child.max = Vec3(n.bounds[3][slot], n.bounds[4][slot], n.bounds[5][slot]);
      EXPECT_TRUE(v.box.contains(child)) << "node " << i << " slot " << slot;
    }
    EXPECT_GE(children, 2) << "node " << i;
  }
  EXPECT_EQ(seen.size(), scene.valid_prims().size());
  for (uint32_t prim : scene.valid_prims()) EXPECT_EQ(seen.count(prim), 1u) << "prim " << prim;
}

TEST(BvhBuilders, EveryBuilderMakesAValidTree) {
  std::vector<Scene> scenes;
  for (const char* name : {"soup", "stadium", "cornell"}) scenes.push_back(make_procedural_scene(name).value());
  if (auto bunny = load_obj(testing::shared_scene_path("bunny_lowres.obj"))) scenes.push_back(std::move(bunny.value()));
  for (const Scene& scene : scenes) {
    for (const BvhBuilderInfo& row : bvh_builder_table()) {
      if (row.splits_triangles) continue;  // a triangle in several leaves: test_bvh_spatial.cpp
      const char* builder = row.name;
      for (int leaf : {1, 4}) {
        for (const char* width : {"2", "4", "8"}) {
          SCOPED_TRACE(scene.name() + " " + builder + " leaf " + std::to_string(leaf) + " width " + width);
          auto bvh = build_structure("bvh", scene, {std::string("builder=") + builder,
                                                    "leaf_size=" + std::to_string(leaf), std::string("width=") + width});
          ASSERT_TRUE(bvh);
          if (const auto* binary = dynamic_cast<const BinaryBvh*>(bvh.value().get()))
            expect_valid_tree(*binary, scene, leaf);
          else if (const auto* wide = dynamic_cast<const WideBvh*>(bvh.value().get()))
            expect_valid_wide_tree(*wide, scene, leaf);
          else if (const auto* wide8 = dynamic_cast<const WideBvh8*>(bvh.value().get()))
            expect_valid_wide_tree(*wide8, scene, leaf);
          else
            FAIL() << "bvh is neither layout";
          EXPECT_LT(bvh.value()->build_stats().max_depth, kMaxBvhDepth);
        }
      }
    }
  }
}

// `width` picks the class at creation: the binary tree for 2, the 4-wide layout for 4, the
// 8-wide one for 8 (the default with AVX2); all are "bvh", report their width and answer alike.
TEST(BvhWidth, PicksTheLayoutClass) {
  const Scene scene = make_procedural_scene("cornell").value();
  auto binary = build_structure("bvh", scene, {"width=2"});
  auto wide = build_structure("bvh", scene, {"width=4"});
  auto fallback = build_structure("bvh", scene, {});
  ASSERT_TRUE(binary && wide && fallback);
  EXPECT_NE(dynamic_cast<const BinaryBvh*>(binary.value().get()), nullptr);
  EXPECT_EQ(dynamic_cast<const WideBvh*>(binary.value().get()), nullptr);
  EXPECT_NE(dynamic_cast<const WideBvh*>(wide.value().get()), nullptr);
  EXPECT_EQ(dynamic_cast<const BinaryBvh*>(wide.value().get()), nullptr);
  // The default (width=auto) is 8 wide where AVX2 runs, else 4 wide (ACCEL_ISA=sse2 in CI).
  if (active_isa() >= Isa::Avx2)
    EXPECT_NE(dynamic_cast<const WideBvh8*>(fallback.value().get()), nullptr);
  else
    EXPECT_NE(dynamic_cast<const WideBvh*>(fallback.value().get()), nullptr);
  for (const auto* s : {binary.value().get(), wide.value().get()}) {
    EXPECT_EQ(s->name(), "bvh");
    const auto extra = s->build_stats().extra;
    ASSERT_FALSE(extra.empty());
    EXPECT_EQ(extra.back().first, "width");
  }
  EXPECT_EQ(binary.value()->build_stats().extra.back().second, "2");
  EXPECT_EQ(wide.value()->build_stats().extra.back().second, "4");
  Rng rng(5);
  const Aabb box = scene.bounds();
  for (int i = 0; i < 2000; ++i) {
    Ray r;
    r.org = box.center() + box.extent() * Vec3(rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f));
    r.dir = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Hit a = binary.value()->intersect(r), b = wide.value()->intersect(r);
    ASSERT_EQ(a.valid(), b.valid()) << "ray " << i;
    if (a.valid()) {
      EXPECT_TRUE(a.prim == b.prim || a.t == b.t) << "ray " << i;
    }
  }
}

TEST(BvhBuilders, InsertionOfIdenticalTrianglesStaysShallow) {
  // An adversarial input for insertion: every cost ties, which grows a chain. The depth
  // limit rebuilds it.
  std::vector<UVec3> t(3000, UVec3(0, 1, 2));
  Scene scene({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, std::move(t));
  for (const BvhBuilderInfo& row : bvh_builder_table()) {
    const char* builder = row.name;
    auto s = build_structure("bvh", scene, {std::string("builder=") + builder, "leaf_size=1"});
    ASSERT_TRUE(s);
    EXPECT_LT(s.value()->build_stats().max_depth, kMaxBvhDepth) << builder;
    Ray r;
    r.org = Vec3(0.2f, 0.2f, 1.0f);
    r.dir = Vec3(0, 0, -1);
    EXPECT_TRUE(s.value()->intersect(r).valid()) << builder;
  }
}

TEST(BvhBuilders, SweepAndBinnedSahCostsAgreeWithinAFewPercent) {
  std::vector<std::string> scenes = {"procedural:soup", "procedural:stadium", "procedural:sphere"};
  for (const char* mesh : {"bunny.obj", "dragon_res4.obj", "spot.obj", "teapot.obj"})
    if (std::filesystem::exists(testing::shared_scene_path(mesh))) scenes.push_back(testing::shared_scene_path(mesh));
  for (const std::string& spec : scenes) {
    const Scene scene = load_scene(spec).value();
    const double sweep = build_structure("bvh", scene, {"builder=sah"}).value()->build_stats().sah_cost;
    const double binned = build_structure("bvh", scene, {"builder=binned_sah", "bins=32"}).value()->build_stats().sah_cost;
    const double median = build_structure("bvh", scene, {"builder=median"}).value()->build_stats().sah_cost;
    EXPECT_NEAR(binned / sweep, 1.0, 0.05) << spec << " sweep " << sweep << " binned " << binned;
    EXPECT_LE(sweep, median * 1.02) << spec << ": the SAH sweep should not lose to the median split";
  }
}

TEST(BvhParams, OutOfRangeIsRejectedWithRange) {
  const Scene scene = four_walls();
  auto s = build_structure("bvh", scene, {"leaf_size=0"});
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("'leaf_size' = '0' is invalid: expected an integer in [1, 64]"), std::string::npos)
      << s.error().message;
  auto t = build_structure("bvh", scene, {"traversal=bfs"});
  ASSERT_FALSE(t);
  EXPECT_NE(t.error().message.find("one of: dfs, ordered, pqueue"), std::string::npos);
}

}  // namespace
}  // namespace accel
