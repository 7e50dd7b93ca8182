// BuildControl: every structure reports monotone progress ending at 1.0, honours a cancel
// set before the start or during the build (then stays safely empty), and builds exactly
// the same structure with a control as without one.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "build_control.h"
#include "ray_gen.h"
#include "registry.h"
#include "scene.h"

namespace accel {
namespace {

/// One structure configuration: registry name and parameters.
struct Config {
  std::string name;
  std::vector<std::string> params;
};

/// Every class of the registry (the BVH's two layouts and the sphere tree included) and
/// the builder variants whose progress is computed differently.
std::vector<Config> configs() {
  return {
      {"brute", {}},
      {"grid", {}},
      {"grid", {"insert=exact"}},
      {"octree", {}},
      {"octree", {"insert=exact"}},
      {"kdtree", {}},
      {"kdtree", {"split=middle"}},
      {"kdtree", {"split=median", "max_depth=20"}},
      {"bvh", {"width=2"}},
      {"bvh", {"width=4"}},
      {"bvh", {"width=2", "builder=binned_sah"}},
      {"bvh", {"width=4", "builder=sbvh"}},  // progress by subtree weights, not triangles
      {"spheretree", {}},
  };
}

std::string label(const Config& c) {
  std::string s = c.name;
  for (const std::string& p : c.params) s += " " + p;
  return s;
}

const Scene& soup() {
  static const Scene scene = make_procedural_scene("soup").value();
  return scene;
}

/// The teapot in the stadium: big enough that a build has many nodes to stop between.
const Scene& stadium() {
  static const Scene scene = make_procedural_scene("stadium").value();
  return scene;
}

Result<std::unique_ptr<Structure>> build(const Config& c, const Scene& scene, BuildControl* control) {
  return build_structure(c.name, scene, c.params, Kernel::Watertight, control);
}

/// A structure whose build was refused: a query, the node list and the stats must work.
void expect_safe_empty(const Structure& s, const Scene& scene) {
  for (const Ray& ray : random_rays(scene.bounds(), 32, 7)) EXPECT_FALSE(s.intersect(ray).valid());
  size_t nodes_with_prims = 0;
  s.for_each_node([&](const NodeView& v) { nodes_with_prims += v.prim_count; });
  (void)s.build_stats();
  (void)s.node_view(0);
  (void)s.node_prims(0);
  // Brute force "nodes" are the scene itself: it must at least not claim any triangle.
  EXPECT_EQ(nodes_with_prims, 0u);
}

TEST(BuildControl, ReportClampsAndCancelSticks) {
  std::vector<double> seen;
  BuildControl control([&](double f) { seen.push_back(f); });
  EXPECT_EQ(control.fraction(), 0.0);
  control.report(0.25);
  control.report(2.0);
  control.report(-1.0);
  EXPECT_EQ(seen, (std::vector<double>{0.25, 1.0, 0.0}));
  EXPECT_FALSE(control.cancelled());
  control.cancel();
  control.cancel();
  EXPECT_TRUE(control.cancelled());
  EXPECT_FALSE(build_cancelled(nullptr));
}

TEST(BuildControl, ProgressSpanMapsThrottlesAndFinishes) {
  std::vector<double> seen;
  BuildControl control([&](double f) { seen.push_back(f); });
  ProgressSpan span(&control, 0.5, 1.0);
  for (int i = 0; i <= 100000; ++i) EXPECT_TRUE(span.advance(double(i) / 100000.0));
  span.finish();
  ASSERT_FALSE(seen.empty());
  EXPECT_LE(seen.size(), 600u);  // throttled to ~1/1024 of the whole build per report
  EXPECT_GE(seen.front(), 0.5);
  EXPECT_EQ(seen.back(), 1.0);
  control.cancel();
  EXPECT_FALSE(span.advance(1.0));
}

TEST(BuildControl, ProgressCounterSumsEveryThreadAndReportsFromItsOwn) {
  std::vector<double> seen;
  std::vector<std::thread::id> reporters;
  BuildControl control([&](double f) {
    seen.push_back(f);
    reporters.push_back(std::this_thread::get_id());
  });
  ProgressSpan span(&control, 0.0, 1.0);
  constexpr uint64_t kPerThread = 100000;
  ProgressCounter counter(&span, 4 * kPerThread);
  // Three other threads and this one add 1 at a time; only this (the counter's) thread reports.
  std::vector<std::thread> others;
  for (int t = 0; t < 3; ++t)
    others.emplace_back([&] {
      for (uint64_t i = 0; i < kPerThread; ++i) counter.add(1);
    });
  for (uint64_t i = 0; i < kPerThread; ++i) counter.add(1);
  for (std::thread& t : others) t.join();
  counter.add(0);  // this thread sees the whole sum now
  ASSERT_FALSE(seen.empty());
  for (size_t i = 1; i < seen.size(); ++i) ASSERT_LE(seen[i - 1], seen[i]);
  EXPECT_GE(seen.back(), 1.0 - 1.0 / 1024.0);  // within the span's reporting step of the whole
  for (std::thread::id id : reporters) EXPECT_EQ(id, std::this_thread::get_id());
  EXPECT_FALSE(counter.stopped());
  // A cancel stops it, seen from any thread, and nothing more is reported.
  control.cancel();
  EXPECT_TRUE(counter.stopped());
  std::thread([&] { EXPECT_TRUE(counter.stopped()); }).join();
  const size_t reports = seen.size();
  counter.add(kPerThread);
  EXPECT_EQ(seen.size(), reports);
}

TEST(BuildControl, ProgressCounterOfSharesNeverPassesOne) {
  BuildControl control;
  ProgressSpan span(&control, 0.0, 1.0);
  ProgressCounter shares(&span, ProgressCounter::kWhole);
  for (int i = 0; i < 3; ++i) shares.add_share(1.0 / 3.0);  // rounded down: a sum just under 1
  EXPECT_LE(control.fraction(), 1.0);
  EXPECT_GT(control.fraction(), 0.999);
  ProgressCounter none(nullptr, 10);  // no span: counts nothing, never stops
  none.add(100);
  EXPECT_FALSE(none.stopped());
}

TEST(BuildControl, ProgressIsMonotoneAndEndsAtOneForEveryStructure) {
  for (const Config& c : configs()) {
    std::vector<double> seen;
    BuildControl control([&](double f) { seen.push_back(f); });
    auto s = build(c, soup(), &control);
    ASSERT_TRUE(s.ok()) << label(c) << ": " << s.error().message;
    ASSERT_GE(seen.size(), 2u) << label(c);
    EXPECT_EQ(seen.front(), 0.0) << label(c);
    EXPECT_EQ(seen.back(), 1.0) << label(c);
    EXPECT_EQ(control.fraction(), 1.0) << label(c);
    for (size_t i = 1; i < seen.size(); ++i)
      ASSERT_LE(seen[i - 1], seen[i]) << label(c) << ": report " << i << " went back";
    // Builders with real work report in between, not just the two ends (brute force has none).
    if (c.name != "brute") {
      EXPECT_GE(seen.size(), 3u) << label(c);
    }
  }
}

TEST(BuildControl, CancelledBeforeStartFailsForEveryStructure) {
  for (const Config& c : configs()) {
    BuildControl control;
    control.cancel();
    auto s = build(c, soup(), &control);
    ASSERT_FALSE(s.ok()) << label(c);
    EXPECT_EQ(s.error().message, cancelled_error().message) << label(c);
    // The same through the Structure interface, which keeps the object: it must be empty.
    auto info = find_structure(c.name).value();
    auto params = ParamSet::parse(info->params, c.params, c.name).value();
    std::unique_ptr<Structure> structure = info->create(params);
    const Status st = structure->build(soup(), params, &control);
    ASSERT_FALSE(st.ok()) << label(c);
    expect_safe_empty(*structure, soup());
  }
}

TEST(BuildControl, CancelledMidwayStopsAtTheNextCheck) {
  for (const Config& c : configs()) {
    if (c.name == "brute") continue;  // nothing to stop: its build is the 0 and the 1.0
    std::vector<double> seen;
    size_t cancel_at = 0;
    BuildControl* self = nullptr;
    BuildControl control([&](double f) {
      seen.push_back(f);
      if (f >= 0.3 && !self->cancelled()) {
        cancel_at = seen.size();
        self->cancel();
      }
    });
    self = &control;
    auto info = find_structure(c.name).value();
    auto params = ParamSet::parse(info->params, c.params, c.name).value();
    std::unique_ptr<Structure> structure = info->create(params);
    const Status st = structure->build(stadium(), params, &control);
    ASSERT_FALSE(st.ok()) << label(c) << " finished despite the cancel";
    EXPECT_EQ(st.error().message, cancelled_error().message) << label(c);
    // "Quickly": the build stopped at its next check, before reporting any further progress.
    EXPECT_EQ(seen.size(), cancel_at) << label(c) << ": reported on after the cancel";
    EXPECT_LT(seen.back(), 1.0) << label(c);
    expect_safe_empty(*structure, stadium());
    // The same object builds normally afterwards.
    ASSERT_TRUE(structure->build(stadium(), params).ok()) << label(c);
    EXPECT_GT(structure->build_stats().prim_references, 0u) << label(c);
  }
}

TEST(BuildControl, AnExternalFlagStopsTheBuildAsCancelDoes) {
  // The CLI's SIGINT flag: set from outside mid-build, seen at the next check.
  for (const Config& c : configs()) {
    if (c.name == "brute") continue;
    std::atomic<bool> flag{false};
    std::vector<double> seen;
    BuildControl control([&](double f) {
      seen.push_back(f);
      if (f >= 0.3) flag.store(true);
    });
    control.set_cancel_flag(&flag);
    EXPECT_FALSE(control.timed_out());
    auto s = build(c, stadium(), &control);
    ASSERT_FALSE(s.ok()) << label(c) << " finished despite the flag";
    EXPECT_EQ(s.error().message, cancelled_error().message) << label(c);
    EXPECT_TRUE(control.cancelled()) << label(c);
    EXPECT_FALSE(control.timed_out()) << label(c);
    EXPECT_LT(seen.back(), 1.0) << label(c);
  }
  BuildControl unset;
  std::atomic<bool> clear{false};
  unset.set_cancel_flag(&clear);
  EXPECT_FALSE(unset.cancelled());
}

TEST(BuildControl, AControlChangesNothingInTheStructure) {
  const std::vector<Ray> rays = random_rays(stadium().bounds(), 400, 11);
  for (const Config& c : configs()) {
    auto plain = build(c, stadium(), nullptr);
    BuildControl control([](double) {});
    auto controlled = build(c, stadium(), &control);
    ASSERT_TRUE(plain.ok() && controlled.ok()) << label(c);
    const BuildStats a = plain.value()->build_stats(), b = controlled.value()->build_stats();
    EXPECT_EQ(a.nodes, b.nodes) << label(c);
    EXPECT_EQ(a.leaves, b.leaves) << label(c);
    EXPECT_EQ(a.empty_leaves, b.empty_leaves) << label(c);
    EXPECT_EQ(a.max_depth, b.max_depth) << label(c);
    EXPECT_EQ(a.prim_references, b.prim_references) << label(c);
    EXPECT_EQ(a.memory_bytes, b.memory_bytes) << label(c);
    EXPECT_EQ(a.leaf_size_histogram, b.leaf_size_histogram) << label(c);
    if (!std::isnan(a.sah_cost)) {
      EXPECT_EQ(a.sah_cost, b.sah_cost) << label(c);
    }
    size_t hits = 0;
    for (const Ray& ray : rays) {
      const Hit ha = plain.value()->intersect(ray), hb = controlled.value()->intersect(ray);
      ASSERT_EQ(ha.prim, hb.prim) << label(c);
      ASSERT_EQ(ha.t, hb.t) << label(c);
      hits += ha.valid();
    }
    EXPECT_GT(hits, 50u) << label(c);
  }
}

}  // namespace
}  // namespace accel
