// Rays file parsing and the hits CSV (docs/hits.md).
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "rays_io.h"

namespace accel {
namespace {

TEST(RaysFile, ParsesDecimalHexInfCommentsAndDefaults) {
  auto rays = parse_rays("# comment\n\n0 0 0 0 0 1\n  0x1.8p+3 -1 2.5e0 1 0 0 0.5 inf\n1 2 3 0 1 0 -1 4\n", "r.txt");
  ASSERT_TRUE(rays) << rays.error().message;
  ASSERT_EQ(rays.value().size(), 3u);
  EXPECT_EQ(rays.value()[0].tmin, 0.0f);
  EXPECT_EQ(rays.value()[0].tmax, kInf);
  EXPECT_EQ(rays.value()[1].org.x, 12.0f);
  EXPECT_EQ(rays.value()[1].org.y, -1.0f);
  EXPECT_EQ(rays.value()[1].tmin, 0.5f);
  EXPECT_EQ(rays.value()[1].tmax, kInf);
  EXPECT_EQ(rays.value()[2].tmin, -1.0f);
  EXPECT_EQ(rays.value()[2].tmax, 4.0f);
}

TEST(RaysFile, HexFloatWithSign) {
  float v;
  ASSERT_TRUE(parse_ray_number("-0x1p-2", &v));
  EXPECT_EQ(v, -0.25f);
  ASSERT_TRUE(parse_ray_number("+inf", &v));
  EXPECT_EQ(v, kInf);
  EXPECT_FALSE(parse_ray_number("1.0x", &v));
  EXPECT_FALSE(parse_ray_number("--1", &v));
  EXPECT_FALSE(parse_ray_number("", &v));
}

struct BadRay {
  const char* text;
  const char* expected;
};

class RaysFileRejects : public ::testing::TestWithParam<BadRay> {};

TEST_P(RaysFileRejects, NamingFileAndLine) {
  auto rays = parse_rays(std::string("0 0 0 0 0 1\n") + GetParam().text + "\n", "rays.txt");
  ASSERT_FALSE(rays);
  EXPECT_EQ(rays.error().message.rfind("rays.txt:2: ", 0), 0u) << rays.error().message;
  EXPECT_NE(rays.error().message.find(GetParam().expected), std::string::npos) << rays.error().message;
}

INSTANTIATE_TEST_SUITE_P(Bad, RaysFileRejects,
                         ::testing::Values(BadRay{"0 0 0 0 0", "expected 6 or 8"},
                                           BadRay{"0 0 0 0 0 1 0", "expected 6 or 8"},
                                           BadRay{"0 0 0 0 0 1 0 1 2", "expected 6 or 8"},
                                           BadRay{"0 0 zero 0 0 1", "malformed number 'zero'"},
                                           BadRay{"0 0 nan 0 0 1", "NaN"},
                                           BadRay{"0 0 0 0 0 inf", "must be finite"},
                                           BadRay{"0 0 0 0 0 0", "zero vector"},
                                           BadRay{"0 0 0 0 0 1 0 nan", "NaN"},
                                           BadRay{"0 0 0 0 0 1 inf inf", "tmin is +inf"}));

TEST(HitsCsv, RowFormat) {
  EXPECT_EQ(format_hit_row(3, Hit{}), "3,-1,inf,0,0\n");
  EXPECT_EQ(format_hit_row(0, Hit{7, 0.1f, 0.25f, 0.5f}), "0,7,0.100000001,0.25,0.5\n");
}

TEST(HitsCsv, AtomicWriteLeavesNoFileOnFailure) {
  const std::string bad = "/nonexistent_dir/hits.csv";
  auto r = write_hits_csv(bad, {Hit{}});
  ASSERT_FALSE(r);
  EXPECT_FALSE(std::filesystem::exists(bad));
  const std::string good = ::testing::TempDir() + "/hits.csv";
  ASSERT_TRUE(write_hits_csv(good, {Hit{}, Hit{1, 2.0f, 0.0f, 0.0f}}));
  std::ifstream in(good);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), "ray,prim,t,u,v\n0,-1,inf,0,0\n1,1,2,0,0\n");
}

}  // namespace
}  // namespace accel
