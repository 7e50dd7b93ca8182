// Numerically hard scenes and rays. Expected answers come from the double-precision kernel
// on the float inputs (core/accuracy.h), or are exact by construction (axis-aligned geometry
// whose t is representable). Every structure with the watertight kernel must answer all of
// them correctly; the Moller-Trumbore kernel is expected to fail some, and the suite reports
// how many.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "batch.h"
#include "check_suites.h"
#include "random.h"
#include "registry.h"
#include "test_support.h"

namespace accel {
namespace {

const std::vector<HardCase>& cached_cases() {
  static const std::vector<HardCase> cases = hard_cases();
  return cases;
}

struct HardConfig {
  std::string structure;
  std::vector<std::string> params;
};

class HardCases : public ::testing::TestWithParam<HardConfig> {};

TEST_P(HardCases, WatertightKernelPassesEveryCase) {
  const HardConfig& c = GetParam();
  for (const HardCase& hc : cached_cases()) {
    const auto ref = testing::reference_hits(hc.scene, hc.rays);
    auto built = build_structure(c.structure, hc.scene, c.params, Kernel::Watertight);
    ASSERT_TRUE(built) << built.error().message;
    const auto hits = trace_all(*built.value(), hc.rays);
    size_t wrong = 0;
    std::string first;
    for (size_t i = 0; i < hits.size(); ++i) {
      std::string why;
      if (!testing::hit_is_correct(hc.scene, hc.rays[i], hits[i], ref[i], &why) && ++wrong <= 3)
        first += "  ray " + std::to_string(i) + ": " + why + "\n";
    }
    EXPECT_EQ(wrong, 0u) << hc.name << " (" << hc.rays.size() << " rays)\n" << first;
  }
}

TEST(HardCasesExact, TminTmaxAreInclusiveToTheUlp) {
  // Checked against the construction, not the reference: t = 3 exactly.
  const auto& cases = cached_cases();
  const auto it = std::find_if(cases.begin(), cases.end(), [](const HardCase& h) { return h.name == "hits_at_tmin_tmax"; });
  ASSERT_NE(it, cases.end());
  for (const std::string& name : structure_names()) {
    auto s = build_structure(name, it->scene, {});
    ASSERT_TRUE(s);
    for (const Ray& r : it->rays) {
      const bool expect_hit = r.tmin <= 3.0f && 3.0f <= r.tmax;
      const Hit h = s.value()->intersect(r);
      ASSERT_EQ(h.valid(), expect_hit) << name << " tmin " << r.tmin << " tmax " << r.tmax;
      if (expect_hit) {
        ASSERT_EQ(h.t, 3.0f) << name;
      }
    }
  }
}

TEST(HardCasesReport, MollerFailuresAreCounted) {
  // Not an assertion on Moller: the lecture's point is that it is not watertight. The counts
  // are reported (ctest --output-on-failure -V shows them; also as test properties).
  size_t total_wrong = 0;
  for (const HardCase& hc : cached_cases()) {
    const auto ref = testing::reference_hits(hc.scene, hc.rays);
    auto built = build_structure("bvh", hc.scene, {}, Kernel::Moller);
    ASSERT_TRUE(built);
    const auto hits = trace_all(*built.value(), hc.rays);
    size_t wrong = 0;
    for (size_t i = 0; i < hits.size(); ++i) wrong += !testing::hit_is_correct(hc.scene, hc.rays[i], hits[i], ref[i]);
    std::cout << "moller on " << hc.name << ": " << wrong << " of " << hc.rays.size() << " rays wrong\n";
    ::testing::Test::RecordProperty("moller_wrong_" + hc.name, int(wrong));
    total_wrong += wrong;
  }
  std::cout << "moller total: " << total_wrong << " wrong\n";
}

std::vector<HardConfig> hard_configs() {
  // brute is left out: it is the same kernel as every structure's leaves, and scanning the
  // stadium for each ray would cost the suite half a minute.
  return {{"grid", {}},
          {"grid", {"resolution=avgsize"}},
          {"octree", {}},
          {"octree", {"order=fixed"}},
          {"kdtree", {}},
          {"kdtree", {"split=middle"}},
          {"bvh", {}},
          {"bvh", {"builder=binned_sah", "traversal=pqueue"}},
          {"bvh", {"builder=bottom_up", "traversal=dfs"}},
          {"bvh", {"builder=sbvh"}},
          {"bvh", {"builder=sbvh", "width=2", "traversal=pqueue", "sbvh_alpha=0"}},
          {"bvh", {"width=2"}},
          {"bvh", {"width=4"}},
          {"bvh", {"width=8"}},
          {"spheretree", {}}};
}

INSTANTIATE_TEST_SUITE_P(Structures, HardCases, ::testing::ValuesIn(hard_configs()),
                         [](const ::testing::TestParamInfo<HardConfig>& param_info) {
                           std::string n = param_info.param.structure;
                           for (const auto& p : param_info.param.params) n += "_" + p;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace accel
