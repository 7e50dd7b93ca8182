#include "structure_suite.h"

#include <bit>

#include "batch.h"
#include "check_suites.h"
#include "registry.h"
#include "test_support.h"

namespace accel::testing {
namespace {

struct SuiteScene {
  std::string key;
  std::function<Scene()> make;
  size_t random_rays;
  int primary_w, primary_h;
};

std::vector<SuiteScene> suite_scenes() {
  std::vector<SuiteScene> scenes;
  for (const std::string& name : procedural_scene_names())
    scenes.push_back({"procedural:" + name, [name] { return make_procedural_scene(name).value(); }, 100000, 160, 120});
  for (const char* edge : {"one_triangle", "coplanar", "identical"})
    scenes.push_back({std::string("edge:") + edge, [edge] { return edge_scene(edge); }, 10000, 40, 30});
  // Small real meshes (<= 12k triangles) when ../shared is present, with 60k random rays
  // each (the reference is brute force, and at 100k these nine were half of its work);
  // the large ones are checked by scripts/verify_shared_meshes.py (docs/reliability.md) to keep ctest short.
  for (const char* file : {"teapot.obj", "cornell_box.obj", "spider.obj", "spot.obj", "holodeck.obj",
                           "bunny_lowres.obj", "WusonOBJ.obj", "scrub_pine.obj", "dragon_res4.obj"}) {
    const std::string path = shared_scene_path(file);
    if (!std::filesystem::exists(path)) continue;
    scenes.push_back({path, [path] { return load_obj(path).value(); }, 60000, 160, 120});
  }
  return scenes;
}

}  // namespace

std::string suite_case_name(const ::testing::TestParamInfo<SuiteCase>& info) {
  std::string name = info.param.structure;
  for (const std::string& kv : info.param.params) name += "_" + kv;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

TEST_P(StructureVsReference, SameHitsAsReferenceOnEveryScene) {
  const SuiteCase& c = GetParam();
  for (const SuiteScene& ss : suite_scenes()) {
    SCOPED_TRACE(ss.key);
    const Workload& w = workload(ss.key, ss.make, ss.random_rays, ss.primary_w, ss.primary_h);
    auto built = build_structure(c.structure, w.scene, c.params);
    ASSERT_TRUE(built) << built.error().message;
    const Structure& s = *built.value();
    const auto hits = trace_all(s, w.rays);
    std::string failures;
    EXPECT_EQ(count_wrong(w, hits, &failures), 0u) << ss.key << "\n" << failures;

    // Recording and counting never change the answer: same prim and bit-identical t. Nor
    // does asking one ray at a time (trace_all asked in batches, intersect_batch()).
    const size_t step = std::max<size_t>(1, w.rays.size() / 500);
    for (size_t i = 0; i < w.rays.size(); i += step) {
      TraceRecorder rec;
      QueryStats q;
      const Hit alone = s.intersect(w.rays[i]);
      ASSERT_EQ(alone.prim, hits[i].prim) << "ray " << i;
      ASSERT_EQ(std::bit_cast<uint32_t>(alone.t), std::bit_cast<uint32_t>(hits[i].t)) << "ray " << i;
      const Hit traced = s.intersect_traced(w.rays[i], rec);
      const Hit counted = s.intersect(w.rays[i], &q);
      ASSERT_EQ(traced.prim, hits[i].prim) << "ray " << i;
      ASSERT_EQ(traced.t, hits[i].t) << "ray " << i;
      ASSERT_EQ(counted.prim, hits[i].prim) << "ray " << i;
      const QueryStats from_events = rec.stats();
      ASSERT_EQ(from_events.prims_tested, q.prims_tested) << "ray " << i;
      ASSERT_EQ(from_events.nodes_visited, q.nodes_visited) << "ray " << i;
      ASSERT_FALSE(rec.events().empty());
      ASSERT_EQ(rec.events().back().kind, TraceEventKind::Done);
      ASSERT_EQ(rec.events().back().prim, hits[i].prim);
    }

    // Every node the viewer may draw has sane bounds.
    const BuildStats stats = s.build_stats();
    EXPECT_GE(stats.build_ms, 0.0);
    EXPECT_GT(stats.memory_bytes + (w.scene.valid_prims().empty() ? 1 : 0), 0u);
  }
}

// Run first by ctest (fixture "reference_cache"): computes every scene's reference answers
// once into the on-disk cache, so the structure tests that run in parallel after it do not
// all compute the same references at the same time.
TEST(SuiteWarmup, ComputeReferences) {
  for (const SuiteScene& ss : suite_scenes()) {
    const Workload& w = workload(ss.key, ss.make, ss.random_rays, ss.primary_w, ss.primary_h);
    EXPECT_EQ(w.reference.size(), w.rays.size()) << ss.key;
  }
}

TEST_P(StructureVsReference, EmptySceneBuildsAndMisses) {
  const SuiteCase& c = GetParam();
  Scene empty;
  auto built = build_structure(c.structure, empty, c.params);
  ASSERT_TRUE(built) << built.error().message;
  for (const Ray& r : random_rays(Aabb{Vec3(-1), Vec3(1)}, 100, 3)) EXPECT_FALSE(built.value()->intersect(r).valid());
}

TEST_P(StructureVsReference, AllDegenerateSceneMisses) {
  const SuiteCase& c = GetParam();
  Scene flat({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}, {0, 0, 1}});
  auto built = build_structure(c.structure, flat, c.params);
  ASSERT_TRUE(built) << built.error().message;
  Ray r;
  r.org = Vec3(0.5f, 0.0f, 1.0f);
  r.dir = Vec3(0, 0, -1);
  EXPECT_FALSE(built.value()->intersect(r).valid());
}


}  // namespace accel::testing
