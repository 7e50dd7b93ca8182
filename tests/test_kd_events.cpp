// The kd-tree builder's parts that must not change the tree: the root's radix sort against
// std::stable_sort, the test that decides where it may run, and the ulp steps of the
// clipping's outward rounding (float_steps.h, the SBVH's as well) against std::nextafter.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "float_steps.h"
#include "structures/kd_events.h"

namespace accel::kd {
namespace {

/// Events with many ties of position and type: positions from a small set of negative,
/// positive, denormal and infinite values (no -0, as where the builder radix sorts).
std::vector<Event> tied_events(size_t n, uint32_t seed) {
  const float positions[] = {-std::numeric_limits<float>::infinity(), -3.5f, -1.0f, -1e-40f, 0.0f, 1e-45f, 0.25f,
                             1.0f, 1.0000001f, 7.0f, 3e38f, std::numeric_limits<float>::infinity()};
  std::mt19937 rng(seed);
  std::vector<Event> events;
  for (uint32_t prim = 0; prim < n; ++prim) {
    const float pos = positions[rng() % std::size(positions)];
    events.emplace_back(pos, prim << 2 | uint32_t(rng() % 3));
  }
  return events;
}

TEST(KdEvents, RadixSortIsTheStableSortByPositionAndType) {
  for (size_t n : {size_t(0), size_t(1), size_t(17), size_t(1000), size_t(100000)}) {
    std::vector<Event> radix = tied_events(n, uint32_t(n) + 1);
    std::vector<Event> stable = radix;
    radix_sort_events(radix);
    std::stable_sort(stable.begin(), stable.end(), EventLess{});
    ASSERT_EQ(radix.size(), stable.size());
    for (size_t i = 0; i < n; ++i) {
      ASSERT_EQ(std::bit_cast<uint32_t>(radix[i].pos), std::bit_cast<uint32_t>(stable[i].pos)) << i;
      ASSERT_EQ(radix[i].prim_type, stable[i].prim_type) << i;  // ties in input order
    }
  }
}

TEST(KdEvents, NegativeZeroIsFoundAndPositiveZeroIsNot) {
  std::vector<Event> events = tied_events(100, 7);
  EXPECT_FALSE(has_negative_zero(events));
  events[42].pos = -0.0f;
  EXPECT_TRUE(has_negative_zero(events));
}

TEST(FloatSteps, StepsAreNextafter) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> values = {0.0f, -0.0f, 1.0f, -1.0f, 1e-45f, -1e-45f, 1.17549435e-38f, -1.17549435e-38f,
                               std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(), 0.1f, -2.5f};
  std::mt19937 rng(3);
  for (int i = 0; i < 100000; ++i) {
    const float f = std::bit_cast<float>(uint32_t(rng()));
    if (!std::isnan(f)) values.push_back(f);
  }
  for (float f : values) {
    if (f != -inf) {
      EXPECT_EQ(std::bit_cast<uint32_t>(step_down(f)), std::bit_cast<uint32_t>(std::nextafter(f, -inf))) << f;
    }
    if (f != inf) {
      EXPECT_EQ(std::bit_cast<uint32_t>(step_up(f)), std::bit_cast<uint32_t>(std::nextafter(f, inf))) << f;
    }
  }
  EXPECT_EQ(step_down(inf), std::numeric_limits<float>::max());
  EXPECT_EQ(step_up(-inf), -std::numeric_limits<float>::max());
}

}  // namespace
}  // namespace accel::kd
