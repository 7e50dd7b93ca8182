// Rays file parsing and the hits CSV (docs/hits.md).
#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

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

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The names in `dir` (to see that no temporary file is left).
std::vector<std::string> names_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicWrite, ErrorsNameThePathAndTheReason) {
  const std::string dir = ::testing::TempDir() + "/atomic_write_errors";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/regular";
  ASSERT_TRUE(write_file_atomic(file, "x"));
  auto under_file = write_file_atomic(file + "/out.csv", "y");
  ASSERT_FALSE(under_file);
  EXPECT_EQ(under_file.error().message, file + "/out.csv: cannot open for writing: Not a directory");
  auto to_dir = write_file_atomic(dir, "y");
  ASSERT_FALSE(to_dir);
  EXPECT_EQ(to_dir.error().message, dir + ": cannot open for writing: Is a directory");
  EXPECT_FALSE(check_writable(dir + "/missing/out.csv"));
  EXPECT_TRUE(check_writable(dir + "/new.csv"));
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"regular"});  // the probe is gone
  EXPECT_EQ(read_all(file), "x");
}

TEST(AtomicWrite, FullDeviceIsAnErrorAndStaysADevice) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  auto r = write_file_atomic("/dev/full", std::string(1000, 'x'));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, "/dev/full: write failed: No space left on device");
  EXPECT_TRUE(std::filesystem::is_character_file("/dev/full"));
  EXPECT_FALSE(std::filesystem::exists("/dev/full.tmp." + std::to_string(::getpid())));
}

TEST(AtomicWrite, CancelledWriteLeavesNothingAndKeepsTheOldFile) {
  const std::string dir = ::testing::TempDir() + "/atomic_write_cancel";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/hits.csv";
  std::atomic<bool> cancel{true};
  auto r = write_hits_csv(file, std::vector<Hit>(10), &cancel);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, file + ": not written (interrupted)");
  EXPECT_TRUE(names_in(dir).empty());
  ASSERT_TRUE(write_file_atomic(file, "old"));
  EXPECT_FALSE(write_file_atomic(file, std::string(3 << 20, 'n'), &cancel));
  EXPECT_EQ(read_all(file), "old");
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"hits.csv"});
}

TEST(AtomicWrite, ALinkStaysALinkToTheNewContent) {
  const std::string dir = ::testing::TempDir() + "/atomic_write_link";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ASSERT_TRUE(write_file_atomic(dir + "/target.csv", "old"));
  std::filesystem::create_symlink("target.csv", dir + "/link.csv");
  ASSERT_TRUE(write_file_atomic(dir + "/link.csv", "new"));
  EXPECT_TRUE(std::filesystem::is_symlink(dir + "/link.csv"));
  EXPECT_EQ(read_all(dir + "/target.csv"), "new");
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"link.csv", "target.csv"}));
}

TEST(RaysFile, MessagesQuoteTheInputPrintablyAndShort) {
  auto escape = parse_rays("0 0 \x1b[2J\x7f 0 0 1\n", "r.txt");
  ASSERT_FALSE(escape);
  EXPECT_EQ(escape.error().message, "r.txt:1: malformed number '\\x1b[2J\\x7f' (field 3)");
  auto long_token = parse_rays("0 0 0 0 0 " + std::string(100000, '1') + "\n", "r.txt");
  ASSERT_FALSE(long_token);
  EXPECT_EQ(long_token.error().message, "r.txt:1: malformed number '" + std::string(40, '1') + "...' (field 6)");
}

TEST(RaysFile, ADirectoryIsAnErrorNotZeroRays) {
  auto r = read_rays(::testing::TempDir());
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("Is a directory"), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace accel
