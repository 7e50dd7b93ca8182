// The memory and time budget (core/memory_budget.h, build_control.h): the CLI's sizes, the
// traversal recorder's byte budget, the time limit, and the adversarial scenes of issue #16
// with the extreme values of every structure's parameters. Each configuration must either
// build within the budget (and then answer exactly as the reference) or stop with one line
// that names the memory limit and the parameter to lower, in bounded time.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <string>
#include <vector>

#include "batch.h"
#include "build_control.h"
#include "memory_budget.h"
#include "oracle.h"
#include "random.h"
#include "ray_gen.h"
#include "registry.h"
#include "structure_suite.h"
#include "test_support.h"

namespace accel::testing {
namespace {

// ---------------------------------------------------------------------------------------
// Sizes as --memory-limit takes them

TEST(MemorySize, ParsesUnitsBinaryPrefixesAndPercent) {
  EXPECT_EQ(parse_memory_size("4G").value(), size_t(4) << 30);
  EXPECT_EQ(parse_memory_size("512M").value(), size_t(512) << 20);
  EXPECT_EQ(parse_memory_size("512MiB").value(), size_t(512) << 20);
  EXPECT_EQ(parse_memory_size("1.5GiB").value(), size_t(3) << 29);
  EXPECT_EQ(parse_memory_size("2097152").value(), size_t(2) << 20);
  const double quarter = 0.25 * double(physical_memory_bytes());
  EXPECT_NEAR(double(parse_memory_size("25%").value()), quarter, 1.0);
  EXPECT_EQ(default_memory_limit(), size_t(kDefaultMemoryFraction * double(physical_memory_bytes())));
}

TEST(MemorySize, RejectsNamingTheOption) {
  for (const char* bad : {"", "abc", "-1G", "0", "12Q", "1e400", "nan", "100000000T", "0.5k", "250%", "G"}) {
    auto r = parse_memory_size(bad, "--memory-limit");
    ASSERT_FALSE(r) << bad;
    EXPECT_NE(r.error().message.find("--memory-limit"), std::string::npos) << r.error().message;
    EXPECT_EQ(r.error().message.find('\n'), std::string::npos) << r.error().message;
  }
}

TEST(MemorySize, FormatsForMessages) {
  EXPECT_EQ(format_bytes(512.0 * (1 << 20)), "512 MiB");
  EXPECT_EQ(format_bytes(1.5 * (1 << 30)), "1.5 GiB");
  EXPECT_EQ(format_bytes(800), "800 B");
}

// ---------------------------------------------------------------------------------------
// The adversarial scenes

Scene identical_triangles(size_t n) {
  std::vector<UVec3> t(n, UVec3(0, 1, 2));
  return Scene({{0, 0, 0}, {1, 0, 0}, {0, 1, 1}}, std::move(t), "identical");
}

/// Long thin triangles crossing the whole scene along x and y, overlapping each other.
Scene overlapping_slivers(size_t n) {
  Rng rng(11);
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (uint32_t i = 0; i < n; ++i) {
    const float a = rng.uniform(), b = rng.uniform();
    if (i % 2) p.insert(p.end(), {{-50, a, b}, {50, a + 1e-3f, b}, {50, a, b + 1e-3f}});
    else p.insert(p.end(), {{a, -50, b}, {a + 1e-3f, 50, b}, {a, 50, b + 1e-3f}});
    t.emplace_back(3 * i, 3 * i + 1, 3 * i + 2);
  }
  return Scene(std::move(p), std::move(t), "slivers");
}

/// One triangle 2000 units across among n tiny ones in the unit cube around its middle.
Scene huge_among_tiny(size_t n) {
  Rng rng(12);
  std::vector<Vec3> p = {{-1000, -1000, 0}, {1000, -1000, 0}, {0, 1000, 500}};
  std::vector<UVec3> t = {{0, 1, 2}};
  for (uint32_t i = 0; i < n; ++i) {
    const Vec3 c(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const uint32_t k = uint32_t(p.size());
    p.insert(p.end(), {c, c + Vec3(1e-3f, 0, 0), c + Vec3(0, 1e-3f, 0)});
    t.emplace_back(k, k + 1, k + 2);
  }
  return Scene(std::move(p), std::move(t), "huge_among_tiny");
}

struct AdversarialScene {
  std::string name;
  Scene scene;
};

/// The four scenes, smaller in the sanitizer run (ACCEL_TEST_RAY_SCALE < 1): its builds are
/// ten times slower, and the shapes, not the counts, are what is adversarial.
const std::vector<AdversarialScene>& adversarial_scenes() {
  static const std::vector<AdversarialScene> scenes = [] {
    const bool small = ray_scale() < 1.0;
    std::vector<AdversarialScene> s;
    s.push_back({"identical", identical_triangles(small ? 500 : 5000)});
    s.push_back({"slivers", overlapping_slivers(small ? 300 : 2000)});
    s.push_back({"huge_among_tiny", huge_among_tiny(small ? 2000 : 20000)});
    // Teapot in a stadium (Haines 1988): procedural:stadium is one, 20k triangles.
    if (!small) s.push_back({"stadium", make_procedural_scene("stadium").value()});
    return s;
  }();
  return scenes;
}

/// A line "KEY: N kB" of /proc/self/status in bytes (0 where /proc cannot tell): VmRSS is
/// the resident memory now, VmHWM its peak since the last reset_peak_memory().
size_t status_bytes(const std::string& wanted) {
  std::ifstream status("/proc/self/status");
  std::string key;
  size_t kb = 0;
  while (status >> key)
    if (key == wanted && status >> kb) return kb << 10;
  return 0;
}
size_t peak_memory_bytes() { return status_bytes("VmHWM:"); }
size_t resident_memory_bytes() { return status_bytes("VmRSS:"); }
bool reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  return bool(clear << "5");
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kInstrumented = true;  // shadow memory and quarantine blur the peak
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kInstrumented = true;
#else
constexpr bool kInstrumented = false;
#endif
#else
constexpr bool kInstrumented = false;
#endif

/// A structure and its parameters, named in the tests as the structure suite names them.
using ExtremeCase = SuiteCase;

/// Every parameter at the end of its range that makes a structure bigger or slower.
std::vector<ExtremeCase> extreme_cases() {
  return {
      {"grid", {"lambda=16"}},
      {"grid", {"resolution=avgsize", "lambda=16"}},
      {"grid", {"insert=bbox", "lambda=16"}},
      {"grid", {"res=1024,1024,64"}},
      {"octree", {"max_depth=40", "max_prims=1"}},
      {"octree", {"max_depth=40", "max_prims=1", "insert=bbox"}},
      {"kdtree", {"max_depth=64", "leaf_size=1", "ci=1000", "ct=0.01", "empty_bonus=0.95"}},
      {"kdtree", {"split=middle", "max_depth=64", "leaf_size=1"}},
      {"kdtree", {"split=median", "max_depth=64", "leaf_size=1", "clip=off"}},
      {"bvh", {"builder=sbvh", "sbvh_budget=4", "sbvh_alpha=0", "leaf_size=1", "bins=256"}},
      {"bvh", {"builder=insertion", "leaf_size=1"}},
      {"bvh", {"builder=bottom_up", "leaf_size=1", "width=2"}},
      {"bvh", {"builder=sah", "leaf_size=1", "width=8"}},
      {"spheretree", {"builder=sbvh", "sbvh_budget=4", "sbvh_alpha=0", "leaf_size=1"}},
      {"spheretree", {"builder=bottom_up", "leaf_size=1"}},
  };
}

class ExtremeParameters : public ::testing::TestWithParam<ExtremeCase> {};

/// A one-line over-budget error: it says which limit and what to change.
void expect_budget_error(const std::string& message, const ExtremeCase& c) {
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(message.find("memory limit"), std::string::npos) << message;
  bool names_a_way_out = message.find("raise the memory limit") != std::string::npos;
  for (const std::string& kv : c.params) names_a_way_out |= message.find(kv.substr(0, kv.find('='))) != std::string::npos;
  EXPECT_TRUE(names_a_way_out) << "names neither a parameter nor the limit: " << message;
}

TEST_P(ExtremeParameters, BuildWithinTheBudgetOrStopNamingTheParameter) {
  const ExtremeCase& c = GetParam();
  // 48 MiB: far below what the grid at lambda=16, the bbox octree or the deep kd-tree would
  // take on these scenes unchecked (hundreds of MB to GB), far above what defaults need.
  const size_t limit = size_t(48) << 20;
  for (const AdversarialScene& as : adversarial_scenes()) {
    SCOPED_TRACE(as.name);
    BuildControl control;
    control.set_memory_limit(limit);
    const bool measured = !kInstrumented && reset_peak_memory();
    const size_t before = resident_memory_bytes();
    const auto start = std::chrono::steady_clock::now();
    auto built = build_structure(c.structure, as.scene, c.params, Kernel::Watertight, &control);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // "None takes minutes": the slowest here (bottom-up clustering of 5000 identical
    // triangles) takes about 3 s in Release.
    EXPECT_LT(seconds, kInstrumented ? 120.0 : 20.0);
    if (measured) {
      // The budget is checked against the builders' estimates of what they hold (nodes,
      // references, per-triangle data), not against every scratch buffer of every task:
      // the peak stays within a quarter above it, plus 16 MiB for the allocator's slack and
      // the thread pool's stacks.
      const size_t peak = peak_memory_bytes();
      EXPECT_LE(peak > before ? peak - before : 0, limit + limit / 4 + (size_t(16) << 20))
          << "peak " << format_bytes(double(peak)) << " from " << format_bytes(double(before));
    }
    if (!built) {
      expect_budget_error(built.error().message, c);
      continue;
    }
    // Built (perhaps shrunk to fit): then it answers exactly as the reference.
    const Structure& s = *built.value();
    const std::vector<Ray> rays = random_rays(as.scene.bounds(), scaled(500), 99);
    const std::vector<Hit> hits = trace_all(s, rays);
    size_t wrong = 0;
    std::string why;
    for (size_t i = 0; i < rays.size(); ++i)
      wrong += !hit_is_correct(as.scene, rays[i], hits[i], reference_closest(as.scene, rays[i]), wrong ? nullptr : &why);
    EXPECT_EQ(wrong, 0u) << why;
  }
}

INSTANTIATE_TEST_SUITE_P(Adversarial, ExtremeParameters, ::testing::ValuesIn(extreme_cases()), suite_case_name);

// Each structure's failure names the parameter that made it big, on a scene that makes it
// big, with a budget of 1 MiB.
TEST(MemoryBudget, ErrorsNameTheParameterToLower) {
  // Full size under the sanitizers too: fewer would fit in 1 MiB, and the builds stop at once.
  const Scene slivers = overlapping_slivers(2000);
  const Scene scattered = huge_among_tiny(20000);
  struct Expect {
    std::string structure;
    std::vector<std::string> params;
    const Scene* scene;
    std::string names;
  };
  const std::vector<Expect> cases = {
      {"grid", {"res=1024,1024,64"}, &slivers, "'res'"},
      {"octree", {"max_depth=40", "max_prims=1"}, &scattered, "max_depth"},
      {"bvh", {"builder=sbvh", "sbvh_budget=4"}, &slivers, "sbvh_budget"},
  };
  for (const Expect& e : cases) {
    BuildControl control;
    control.set_memory_limit(size_t(1) << 20);
    auto built = build_structure(e.structure, *e.scene, e.params, Kernel::Watertight, &control);
    ASSERT_FALSE(built) << e.structure << " built within 1 MiB";
    EXPECT_NE(built.error().message.find(e.names), std::string::npos) << built.error().message;
    EXPECT_NE(built.error().message.find("memory limit 1 MiB"), std::string::npos) << built.error().message;
  }
}

// ---------------------------------------------------------------------------------------
// The time limit

TEST(TimeLimit, StopsASlowBuildWithTheTimeLimitNamed) {
  // Bottom-up clustering of identical triangles: every pair is equally good, seconds of work.
  const Scene scene = identical_triangles(ray_scale() < 1.0 ? 2000 : 8000);
  BuildControl control;
  control.set_time_limit(0.2);
  const auto start = std::chrono::steady_clock::now();
  auto built = build_structure("bvh", scene, {"builder=bottom_up"}, Kernel::Watertight, &control);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_FALSE(built);
  EXPECT_TRUE(control.timed_out());
  EXPECT_LT(seconds, 0.2 + (kInstrumented ? 10.0 : 2.0));
}

TEST(TimeLimit, NoneByDefaultAndUntouchedBuildsFinish) {
  BuildControl control;
  EXPECT_EQ(control.time_limit(), 0.0);
  EXPECT_FALSE(control.cancelled());
  control.set_time_limit(60.0);
  auto built = build_structure("kdtree", make_procedural_scene("sphere").value(), {}, Kernel::Watertight, &control);
  ASSERT_TRUE(built) << built.error().message;
  EXPECT_FALSE(control.timed_out());
}

// ---------------------------------------------------------------------------------------
// The traversal recorder's budget

TEST(TraceBudget, ARecordingPastItsBudgetKeepsTheAnswerAndSaysSo) {
  const Scene scene = make_procedural_scene("soup").value();
  auto built = build_structure("brute", scene, {});
  ASSERT_TRUE(built);
  const Structure& s = *built.value();
  const std::vector<Ray> rays = random_rays(scene.bounds(), 50, 5);
  for (const Ray& r : rays) {
    const Hit plain = s.intersect(r);
    TraceRecorder full;
    TraceRecorder tiny(4096);  // brute force makes ~10k steps per ray: far past 4 KiB
    const Hit recorded = s.intersect_traced(r, full);
    const Hit truncated = s.intersect_traced(r, tiny);
    // Recording, within its budget or past it, changes nothing in the answer.
    EXPECT_EQ(recorded.prim, plain.prim);
    EXPECT_EQ(recorded.t, plain.t);
    EXPECT_EQ(truncated.prim, plain.prim);
    EXPECT_EQ(truncated.t, plain.t);
    EXPECT_FALSE(full.truncated());
    EXPECT_TRUE(tiny.truncated());
    EXPECT_LT(tiny.events().size(), full.events().size());
    ASSERT_FALSE(tiny.events().empty());
    EXPECT_EQ(tiny.events().back().kind, TraceEventKind::Done);
    EXPECT_EQ(tiny.events().back().prim, plain.prim);
  }
}

}  // namespace
}  // namespace accel::testing
