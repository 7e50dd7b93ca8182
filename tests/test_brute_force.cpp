// Brute force with the float watertight kernel against the double-precision reference,
// every fourth of the suite's 100k random rays (plus primary rays) per procedural scene.
#include <atomic>

#include <gtest/gtest.h>

#include "batch.h"
#include "ray_gen.h"
#include "structures/brute_force.h"
#include "registry.h"
#include "test_support.h"

namespace accel {
namespace {

class BruteForceScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(BruteForceScenes, WatertightMatchesDoubleReference) {
  const std::string name = GetParam();
  const auto& all = testing::workload("procedural:" + name, [&] { return make_procedural_scene(name).value(); },
                                      100000, 160, 120);
  // Every fourth ray of the suite's workload (its references are cached): every structure
  // already runs this kernel on all of them, and brute force tests each ray against every
  // triangle, so a quarter (30k rays per scene) keeps the test to seconds.
  testing::Workload w{all.scene, {}, {}};
  for (size_t i = 0; i < all.rays.size(); i += 4) {
    w.rays.push_back(all.rays[i]);
    w.reference.push_back(all.reference[i]);
  }
  auto s = build_structure("brute", w.scene, {});
  ASSERT_TRUE(s);
  const auto hits = trace_all(*s.value(), w.rays);
  std::string failures;
  EXPECT_EQ(testing::count_wrong(w, hits, &failures), 0u) << failures;
  size_t hit_count = 0;
  for (const Hit& h : hits) hit_count += h.valid();
  EXPECT_GT(hit_count, w.rays.size() / 10) << "workload should mostly hit";
}

INSTANTIATE_TEST_SUITE_P(Procedural, BruteForceScenes, ::testing::ValuesIn(procedural_scene_names()));

TEST(BruteForce, TraceAllStopsAtACancelFlag) {
  auto scene = make_procedural_scene("cornell").value();
  auto s = build_structure("brute", scene, {});
  ASSERT_TRUE(s);
  const std::vector<Ray> rays = random_rays(scene.bounds(), 5000, 3);
  std::atomic<bool> cancel{false};
  const auto with_flag = trace_all(*s.value(), rays, 2, nullptr, &cancel);
  const auto without = trace_all(*s.value(), rays, 2);
  ASSERT_EQ(with_flag.size(), without.size());
  for (size_t i = 0; i < rays.size(); ++i)  // unset: the same answers
    ASSERT_TRUE(with_flag[i].prim == without[i].prim && with_flag[i].t == without[i].t) << i;
  cancel.store(true);
  size_t answered = 0;
  for (const Hit& h : trace_all(*s.value(), rays, 2, nullptr, &cancel)) answered += h.valid();
  EXPECT_EQ(answered, 0u) << "set before the start: every ray is skipped";
}

TEST(BruteForce, DegenerateTrianglesAreNeverHit) {
  // A zero-area triangle in front of a real one: the ray passes "through" it.
  Scene scene({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {2, 0, 1}},
              {{3, 4, 5}, {0, 1, 2}});
  auto s = build_structure("brute", scene, {});
  ASSERT_TRUE(s);
  Ray r;
  r.org = Vec3(0.5f, 0.0f, 2.0f);
  r.dir = Vec3(0, 0, -1);
  const Hit h = s.value()->intersect(r);
  EXPECT_EQ(h.prim, 1);
  EXPECT_FLOAT_EQ(h.t, 2.0f);
}

TEST(BruteForce, EmptySceneMisses) {
  Scene empty;
  auto s = build_structure("brute", empty, {});
  ASSERT_TRUE(s);
  EXPECT_FALSE(s.value()->intersect(Ray{}).valid());
}

TEST(BruteForce, RecordingNeverChangesTheAnswer) {
  auto scene = make_procedural_scene("cornell").value();
  auto built = build_structure("brute", scene, {});
  ASSERT_TRUE(built);
  auto s = std::move(built.value());
  for (const Ray& r : random_rays(scene.bounds(), 200, 9)) {
    TraceRecorder rec;
    QueryStats q;
    const Hit a = s->intersect(r), b = s->intersect_traced(r, rec), c = s->intersect(r, &q);
    EXPECT_EQ(a.prim, b.prim);
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(a.prim, c.prim);
    EXPECT_EQ(rec.stats().prims_tested, q.prims_tested);
    EXPECT_EQ(q.prims_tested, scene.valid_prims().size());
    ASSERT_FALSE(rec.events().empty());
    EXPECT_EQ(rec.events().back().kind, TraceEventKind::Done);
    EXPECT_EQ(rec.events().back().prim, a.prim);
  }
}

}  // namespace
}  // namespace accel
