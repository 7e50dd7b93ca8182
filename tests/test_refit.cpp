// Refit: moved vertices, same triangles. The hierarchies (bvh width 2 and 4, sphere tree)
// keep their nodes and primitive lists and get new bounds that answer exactly the reference
// hits of the moved scene; refitting unmoved vertices reproduces the build; the spatial
// subdivisions refuse; bad input is an error. Also Scene::move_vertices itself.
#include <cstring>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "batch.h"
#include "registry.h"
#include "structure_suite.h"
#include "structures/bvh.h"
#include "structures/sphere_tree.h"
#include "test_support.h"

namespace accel::testing {
namespace {

// ============================================================================
// Helpers: the wave, snapshots of a structure, the moved workloads
// ============================================================================

/// A deterministic wave: every vertex displaced on all three axes by up to 3% of the scene's
/// size, smoothly in space (neighbouring triangles stay connected, none collapses). `phase`
/// picks the frame of the animation.
std::vector<Vec3> wave(const Scene& scene, float phase) {
  const Vec3 e = scene.bounds().extent();
  const float size = std::max(e.x, std::max(e.y, e.z));
  const float amplitude = 0.03f * size, k = 2.0f * 3.14159265f * 3.0f / size;
  std::vector<Vec3> moved = scene.positions();
  for (Vec3& p : moved)
    p += amplitude * Vec3(std::sin(k * p.y + phase), std::sin(k * p.z + 2.0f * phase), std::sin(k * p.x + 3.0f * phase));
  return moved;
}

/// Everything a structure shows of its nodes: topology (ids, depths, leaves, primitive
/// lists in order) and bounds. For the 4-wide layout also the SIMD nodes' child boxes.
struct Snapshot {
  std::vector<NodeView> views;
  std::vector<std::vector<uint32_t>> prims;
  std::vector<WideNode> wide;  ///< by node id (inner nodes of a WideBvh; zeros otherwise)
};

Snapshot snapshot(const Structure& s) {
  Snapshot snap;
  s.for_each_node([&](const NodeView& v) {
    snap.views.push_back(v);
    snap.prims.push_back(s.node_prims(v.id));
  });
  if (const auto* wide = dynamic_cast<const WideBvh*>(&s)) {
    snap.wide.resize(snap.views.size());
    for (const NodeView& v : snap.views)
      if (!v.leaf) snap.wide[v.id] = wide->wide_node(v.id);
  }
  return snap;
}

/// Same nodes in the same order with the same triangles.
void expect_same_topology(const Snapshot& a, const Snapshot& b) {
  ASSERT_EQ(a.views.size(), b.views.size());
  for (size_t i = 0; i < a.views.size(); ++i) {
    ASSERT_EQ(a.views[i].id, b.views[i].id);
    ASSERT_EQ(a.views[i].depth, b.views[i].depth) << "node " << i;
    ASSERT_EQ(a.views[i].leaf, b.views[i].leaf) << "node " << i;
    ASSERT_EQ(a.views[i].prim_count, b.views[i].prim_count) << "node " << i;
    ASSERT_EQ(a.prims[i], b.prims[i]) << "node " << i;
  }
}

/// Same topology and equal bounds (==: the sign of a zero bound may come out otherwise than
/// from the builder's unions, which no test of a ray can tell apart).
void expect_same_bounds(const Snapshot& a, const Snapshot& b) {
  expect_same_topology(a, b);
  for (size_t i = 0; i < a.views.size(); ++i) {
    ASSERT_EQ(a.views[i].box.min, b.views[i].box.min) << "node " << i;
    ASSERT_EQ(a.views[i].box.max, b.views[i].box.max) << "node " << i;
    ASSERT_EQ(a.views[i].sphere.center, b.views[i].sphere.center) << "node " << i;
    ASSERT_EQ(a.views[i].sphere.radius, b.views[i].sphere.radius) << "node " << i;
  }
  ASSERT_EQ(a.wide.size(), b.wide.size());
  for (size_t i = 0; i < a.wide.size(); ++i)
    for (int row = 0; row < 6; ++row)
      for (int slot = 0; slot < 4; ++slot) ASSERT_EQ(a.wide[i].bounds[row][slot], b.wide[i].bounds[row][slot]) << i;
}

/// Bit-identical bounds (the same code run with different thread counts).
void expect_identical_bits(const Snapshot& a, const Snapshot& b) {
  expect_same_topology(a, b);
  for (size_t i = 0; i < a.views.size(); ++i) {
    ASSERT_EQ(std::memcmp(&a.views[i].box, &b.views[i].box, sizeof(Aabb)), 0) << "node " << i;
    ASSERT_EQ(std::memcmp(&a.views[i].sphere, &b.views[i].sphere, sizeof(BoundingSphere)), 0) << "node " << i;
  }
  ASSERT_EQ(a.wide.size(), b.wide.size());
  for (size_t i = 0; i < a.wide.size(); ++i) ASSERT_EQ(std::memcmp(&a.wide[i], &b.wide[i], sizeof(WideNode)), 0) << i;
}

/// After a refit every bound is tight around what it holds: a leaf's box is the union of its
/// triangles' boxes, an inner node's the union of its children's (which each slot of a wide
/// node stores), and a sphere holds every vertex below it (checked in double).
void expect_bounds_hold(const Scene& scene, const Snapshot& s) {
  const size_t n = s.views.size();
  for (size_t i = 0; i < n; ++i) {
    const NodeView& v = s.views[i];
    // Depth-first ids: the subtree of i is i and the following ids deeper than it.
    size_t end = i + 1;
    while (end < n && s.views[end].depth > v.depth) ++end;
    Aabb expected;
    std::vector<size_t> children;
    if (v.leaf) {
      for (uint32_t prim : s.prims[i]) expected.extend(scene.triangle_bounds(prim));
    } else {
      for (size_t j = i + 1; j < end; ++j)
        if (s.views[j].depth == v.depth + 1) {
          children.push_back(j);
          expected.extend(s.views[j].box);
        }
    }
    ASSERT_EQ(v.box.min, expected.min) << "node " << i;
    ASSERT_EQ(v.box.max, expected.max) << "node " << i;
    if (!s.wide.empty() && !v.leaf) {
      const WideNode& w = s.wide[i];
      for (size_t slot = 0; slot < 4; ++slot) {
        const Aabb slot_box{{w.bounds[0][slot], w.bounds[1][slot], w.bounds[2][slot]},
                            {w.bounds[3][slot], w.bounds[4][slot], w.bounds[5][slot]}};
        if (slot >= children.size()) {
          ASSERT_TRUE(slot_box.empty()) << "node " << i << " slot " << slot;
          continue;
        }
        ASSERT_EQ(slot_box.min, s.views[children[slot]].box.min) << "node " << i << " slot " << slot;
        ASSERT_EQ(slot_box.max, s.views[children[slot]].box.max) << "node " << i << " slot " << slot;
      }
    }
    if (v.sphere.radius >= 0.0f) {
      for (size_t j = i; j < end; ++j)
        for (uint32_t prim : s.prims[j])
          for (int k = 0; k < 3; ++k)
            ASSERT_LE(glm::length(DVec3(scene.vertex(prim, k)) - DVec3(v.sphere.center)), double(v.sphere.radius))
                << "node " << i;
    }
  }
}

/// The scenes refitted: the procedural ones and, when ../shared is there, a small real mesh.
std::vector<std::string> refit_scenes() {
  std::vector<std::string> specs;
  for (const std::string& name : procedural_scene_names()) specs.push_back("procedural:" + name);
  if (std::filesystem::exists(shared_scene_path("bunny_lowres.obj"))) specs.push_back(shared_scene_path("bunny_lowres.obj"));
  return specs;
}

const Scene& base_scene(const std::string& spec) {
  static std::map<std::string, Scene> cache;
  auto it = cache.find(spec);
  if (it == cache.end()) it = cache.emplace(spec, load_scene(spec).value()).first;
  return it->second;
}

/// The scene moved by wave(phase), its rays and their reference hits.
const Workload& moved_workload(const std::string& spec, float phase) {
  return workload("refit:" + spec + ":" + std::to_string(phase),
                  [&] {
                    const Scene& base = base_scene(spec);
                    return Scene(wave(base, phase), base.triangles(), base.name());
                  },
                  20000, 64, 48);
}

/// The wave phases every refit configuration is checked at.
constexpr float kPhases[] = {0.5f, 2.0f};

// Run first by ctest with SuiteWarmup (fixture "reference_cache"): the moved scenes'
// reference answers, computed once instead of by every configuration at the same time.
TEST(RefitWarmup, ComputeReferences) {
  for (const std::string& spec : refit_scenes())
    for (float phase : kPhases) EXPECT_FALSE(moved_workload(spec, phase).reference.empty()) << spec;
}

/// The structure's hits are correct for `w` by docs/hits.md's rule.
void expect_reference_hits(const Structure& s, const Workload& w) {
  std::string failures;
  EXPECT_EQ(count_wrong(w, trace_all(s, w.rays), &failures), 0u) << failures;
}

std::unique_ptr<Structure> build(const SuiteCase& c, const Scene& scene) {
  auto built = build_structure(c.structure, scene, c.params);
  EXPECT_TRUE(built) << built.error().message;
  return built ? std::move(built.value()) : nullptr;
}

// ============================================================================
// The refittable hierarchies, per configuration
// ============================================================================

class Refit : public ::testing::TestWithParam<SuiteCase> {};

INSTANTIATE_TEST_SUITE_P(
    Hierarchies, Refit,
    ::testing::Values(SuiteCase{"bvh", {"width=2"}},
                      SuiteCase{"bvh", {"width=2", "builder=binned_sah", "traversal=pqueue"}},
                      SuiteCase{"bvh", {"width=2", "builder=insertion", "traversal=dfs", "leaf_size=1"}},
                      SuiteCase{"bvh", {"width=4"}},
                      SuiteCase{"bvh", {"width=4", "builder=binned_sah", "traversal=dfs"}},
                      SuiteCase{"bvh", {"width=4", "builder=bottom_up", "traversal=pqueue", "leaf_size=16"}},
                      SuiteCase{"bvh", {"width=4", "builder=median", "leaf_size=1"}},
                      SuiteCase{"spheretree", {}},
                      SuiteCase{"spheretree", {"builder=binned_sah", "traversal=pqueue"}},
                      SuiteCase{"spheretree", {"builder=median", "traversal=dfs", "leaf_size=1"}}),
    suite_case_name);

TEST_P(Refit, MovedVerticesGiveReferenceHitsWithTheSameTopology) {
  for (const std::string& spec : refit_scenes()) {
    SCOPED_TRACE(spec);
    // The viewer's use: the scene the structure was built over, moved in place, then refit.
    Scene scene = base_scene(spec);
    auto s = build(GetParam(), scene);
    ASSERT_TRUE(s);
    const Snapshot built = snapshot(*s);
    const BuildStats before = s->build_stats();
    for (float phase : kPhases) {
      SCOPED_TRACE(phase);
      const Workload& w = moved_workload(spec, phase);
      ASSERT_TRUE(scene.move_vertices(w.scene.positions()));
      ASSERT_EQ(scene.valid_prims(), base_scene(spec).valid_prims()) << "the wave must not collapse a triangle";
      const Status refit = s->refit(scene);
      ASSERT_TRUE(refit) << refit.error().message;
      expect_reference_hits(*s, w);
      const Snapshot moved = snapshot(*s);
      expect_same_topology(built, moved);
      expect_bounds_hold(scene, moved);
      const BuildStats after = s->build_stats();
      EXPECT_EQ(after.nodes, before.nodes);
      EXPECT_EQ(after.prims, before.prims);
      EXPECT_EQ(after.max_depth, before.max_depth);
      EXPECT_EQ(after.leaf_size_histogram, before.leaf_size_histogram);
      EXPECT_EQ(after.build_ms, before.build_ms);
      EXPECT_GE(after.refit_ms, 0.0);
    }
  }
}

TEST_P(Refit, UnmovedVerticesReproduceTheBuild) {
  for (const std::string& spec : refit_scenes()) {
    SCOPED_TRACE(spec);
    Scene scene = base_scene(spec);
    auto s = build(GetParam(), scene);
    ASSERT_TRUE(s);
    EXPECT_TRUE(std::isnan(s->build_stats().refit_ms)) << "no refit yet";
    const Snapshot built = snapshot(*s);
    const std::vector<Ray> rays = random_rays(scene.bounds(), 5000, 77);
    const std::vector<Hit> hits = trace_all(*s, rays);
    const double sah_cost = s->build_stats().sah_cost;

    // Refit in place, then after a move and a move back: the build's bounds every time.
    ASSERT_TRUE(s->refit(scene));
    expect_same_bounds(built, snapshot(*s));
    ASSERT_TRUE(scene.move_vertices(wave(scene, 1.0f)));
    ASSERT_TRUE(s->refit(scene));
    ASSERT_TRUE(scene.move_vertices(base_scene(spec).positions()));
    ASSERT_TRUE(s->refit(scene));
    expect_same_bounds(built, snapshot(*s));
    EXPECT_EQ(s->build_stats().sah_cost, sah_cost);

    const std::vector<Hit> again = trace_all(*s, rays);
    for (size_t i = 0; i < rays.size(); ++i) {
      ASSERT_EQ(again[i].prim, hits[i].prim) << "ray " << i;
      ASSERT_EQ(again[i].t, hits[i].t) << "ray " << i;
    }
  }
}

TEST_P(Refit, ToAnotherSceneObjectWithTheSameTriangles) {
  // The contract allows refitting to a different Scene (e.g. a copy moved off-thread): it
  // replaces the build's scene.
  const std::string spec = "procedural:sphere";
  const Scene& base = base_scene(spec);
  auto s = build(GetParam(), base);
  ASSERT_TRUE(s);
  const Workload& w = moved_workload(spec, 0.5f);
  ASSERT_TRUE(s->refit(w.scene));
  expect_reference_hits(*s, w);
  expect_bounds_hold(w.scene, snapshot(*s));
}

TEST_P(Refit, ChangedValidTrianglesAreAnErrorAndLeaveTheStructureAsItWas) {
  const std::string spec = "procedural:soup";
  Scene scene = base_scene(spec);
  auto s = build(GetParam(), scene);
  ASSERT_TRUE(s);
  const Snapshot built = snapshot(*s);

  // A triangle collapses to a point: it was built over but is degenerate now.
  std::vector<Vec3> p = scene.positions();
  const UVec3 t = scene.triangles()[17];
  p[t.y] = p[t.x];
  p[t.z] = p[t.x];
  ASSERT_TRUE(scene.move_vertices(p));
  ASSERT_TRUE(scene.degenerate(17));
  Status r = s->refit(scene);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("triangle 17 is degenerate now"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("rebuild"), std::string::npos) << r.error().message;
  expect_same_bounds(built, snapshot(*s));

  // A scene with other triangles (fewer of them): an error, not a crash.
  r = s->refit(base_scene("procedural:sphere"));
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("cannot refit"), std::string::npos) << r.error().message;
  expect_same_bounds(built, snapshot(*s));

  // Back to the build's vertices the refit works again, and the structure answers as built.
  ASSERT_TRUE(scene.move_vertices(base_scene(spec).positions()));
  ASSERT_TRUE(s->refit(scene));
  expect_same_bounds(built, snapshot(*s));
}

TEST_P(Refit, ATriangleThatBecameValidIsAnError) {
  // Triangle 1 is degenerate at build time (collinear), so the structure does not hold it;
  // once it has area it must be found, and only a rebuild can put it in.
  Scene scene({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}}, {{0, 1, 2}, {3, 4, 5}});
  ASSERT_EQ(scene.valid_prims().size(), 1u);
  auto s = build(GetParam(), scene);
  ASSERT_TRUE(s);
  std::vector<Vec3> p = scene.positions();
  p[5] = Vec3(4, 1, 0);
  ASSERT_TRUE(scene.move_vertices(p));
  ASSERT_EQ(scene.valid_prims().size(), 2u);
  const Status r = s->refit(scene);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("became valid"), std::string::npos) << r.error().message;
}

TEST_P(Refit, EmptyStructureRefitsToAnEmptyScene) {
  Scene empty;
  auto s = build(GetParam(), empty);
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->refit(empty));
  EXPECT_EQ(s->build_stats().nodes, 0u);
  EXPECT_FALSE(s->refit(base_scene("procedural:sphere"))) << "an empty structure holds none of its triangles";
}

TEST_P(Refit, SameResultWithOneOrFourThreads) {
  // Big enough for the parallel subtrees (thousands of nodes) and the scene's parallel pass.
  const std::string spec = "procedural:stadium";
  Scene scene_1 = base_scene(spec), scene_4 = base_scene(spec);
  auto s1 = build(GetParam(), scene_1);
  auto s4 = build(GetParam(), scene_4);
  ASSERT_TRUE(s1 && s4);
  expect_identical_bits(snapshot(*s1), snapshot(*s4));
  ASSERT_GT(s1->build_stats().nodes, 2048u);
  const std::vector<Vec3> moved = wave(scene_1, 0.7f);
  tbb::task_arena one(1), four(4);
  one.execute([&] {
    ASSERT_TRUE(scene_1.move_vertices(moved));
    ASSERT_TRUE(s1->refit(scene_1));
  });
  four.execute([&] {
    ASSERT_TRUE(scene_4.move_vertices(moved));
    ASSERT_TRUE(s4->refit(scene_4));
  });
  ASSERT_EQ(scene_1.valid_prims(), scene_4.valid_prims());
  ASSERT_EQ(std::memcmp(&scene_1.bounds(), &scene_4.bounds(), sizeof(Aabb)), 0);
  for (uint32_t i = 0; i < scene_1.triangle_count(); ++i)
    ASSERT_EQ(std::memcmp(&scene_1.triangle_bounds(i), &scene_4.triangle_bounds(i), sizeof(Aabb)), 0) << i;
  expect_identical_bits(snapshot(*s1), snapshot(*s4));
  const std::vector<Ray> rays = random_rays(scene_1.bounds(), 2000, 5);
  const std::vector<Hit> h1 = trace_all(*s1, rays), h4 = trace_all(*s4, rays);
  for (size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(h1[i].prim, h4[i].prim) << "ray " << i;
    ASSERT_EQ(h1[i].t, h4[i].t) << "ray " << i;
  }
}

// ============================================================================
// Structures that cannot refit; Scene::move_vertices
// ============================================================================

TEST(RefitUnsupported, SpatialSubdivisionsAskForARebuild) {
  Scene scene = base_scene("procedural:sphere");
  for (const char* name : {"grid", "octree", "kdtree"}) {
    SCOPED_TRACE(name);
    auto s = build(SuiteCase{name, {}}, scene);
    ASSERT_TRUE(s);
    const Snapshot built = snapshot(*s);
    const Status r = s->refit(scene);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().message.rfind(std::string(name) + " cannot refit: rebuild", 0), 0u) << r.error().message;
    EXPECT_TRUE(std::isnan(s->build_stats().refit_ms));
    expect_same_bounds(built, snapshot(*s));
  }
}

TEST(SceneMoveVertices, RecomputesWhatDerivesFromThePositions) {
  const Scene& base = base_scene("procedural:cornell");
  Scene moved = base;
  const std::vector<Vec3> p = wave(base, 0.3f);
  ASSERT_TRUE(moved.move_vertices(p));
  const Scene fresh(p, base.triangles(), base.name());
  EXPECT_EQ(moved.positions(), fresh.positions());
  EXPECT_EQ(moved.triangles(), base.triangles());
  EXPECT_EQ(moved.valid_prims(), fresh.valid_prims());
  EXPECT_EQ(moved.bounds().min, fresh.bounds().min);
  EXPECT_EQ(moved.bounds().max, fresh.bounds().max);
  EXPECT_EQ(moved.name(), base.name());
  for (uint32_t i = 0; i < fresh.triangle_count(); ++i) {
    ASSERT_EQ(moved.triangle_bounds(i).min, fresh.triangle_bounds(i).min) << i;
    ASSERT_EQ(moved.triangle_bounds(i).max, fresh.triangle_bounds(i).max) << i;
    ASSERT_EQ(moved.centroid(i), fresh.centroid(i)) << i;
    ASSERT_EQ(moved.degenerate(i), fresh.degenerate(i)) << i;
  }
}

TEST(SceneMoveVertices, TracksTrianglesTurningDegenerateAndBack) {
  Scene scene({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  ASSERT_TRUE(scene.move_vertices(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}));
  EXPECT_TRUE(scene.degenerate(0));
  EXPECT_TRUE(scene.valid_prims().empty());
  EXPECT_EQ(scene.degenerate_count(), 1u);
  ASSERT_TRUE(scene.move_vertices(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 0, 5}}));
  EXPECT_FALSE(scene.degenerate(0));
  EXPECT_EQ(scene.valid_prims(), std::vector<uint32_t>{0});
  EXPECT_EQ(scene.bounds().max, Vec3(1, 0, 5));
}

TEST(SceneMoveVertices, WrongCountOrNonFiniteIsAnErrorAndChangesNothing) {
  const Scene& base = base_scene("procedural:sphere");
  Scene scene = base;
  std::vector<Vec3> p = scene.positions();
  p.pop_back();
  Status r = scene.move_vertices(p);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find(std::to_string(p.size()) + " positions given, the scene has " +
                                   std::to_string(base.vertex_count())),
            std::string::npos)
      << r.error().message;
  p = wave(base, 1.0f);
  p[42].y = std::nanf("");
  r = scene.move_vertices(p);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("vertex 42"), std::string::npos) << r.error().message;
  p[42].y = kInf;
  EXPECT_FALSE(scene.move_vertices(p));
  EXPECT_EQ(scene.positions(), base.positions());
  EXPECT_EQ(scene.triangle_bounds(0).min, base.triangle_bounds(0).min);
  EXPECT_EQ(scene.bounds().max, base.bounds().max);
}

}  // namespace
}  // namespace accel::testing
