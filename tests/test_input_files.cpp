// Files on demand (input_files.h): the readers of scenes, 2D scenes, rays files and (through
// read_input_file) playlists, scripts and bench results ask the installed fetcher for a
// missing file at the moment they open it, and only then. The web
// page's fetcher copies from the served folder; here a fetcher writes the file itself.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "input_files.h"
#include "rays_io.h"
#include "scene.h"

namespace accel {
namespace {

namespace fs = std::filesystem;

/// A fresh folder as the working directory (the fetcher is asked for relative paths only,
/// as the page's folder is its working directory), and a fetcher installed for the test's
/// duration that records what it was asked for and writes `contents` when it has them.
class InputFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    home_ = fs::current_path();
    dir_ = fs::temp_directory_path() / ("accel_input_files_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::current_path(dir_);
    set_input_fetcher([this](const std::string& path) -> Status {
      asked_.push_back(path);
      if (contents_.empty()) return make_error(path + ": cannot open (fetched http://x/" + path + ": 404)");
      std::ofstream(path) << contents_;
      return {};
    });
  }
  void TearDown() override {
    set_input_fetcher(nullptr);
    fs::current_path(home_);
    fs::remove_all(dir_);
  }
  static std::string file(const std::string& name) { return name; }

  fs::path home_, dir_;
  std::vector<std::string> asked_;
  std::string contents_;
};

constexpr const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

TEST_F(InputFiles, AMissingSceneIsFetchedWhenOpened) {
  contents_ = kTriangleObj;
  auto scene = load_scene(file("later.obj"));
  ASSERT_TRUE(scene) << scene.error().message;
  EXPECT_EQ(scene.value().triangle_count(), 1u);
  EXPECT_EQ(asked_, std::vector<std::string>{file("later.obj")});
}

TEST_F(InputFiles, AnExistingFileIsNotFetched) {
  std::ofstream(file("here.obj")) << kTriangleObj;
  ASSERT_TRUE(load_scene(file("here.obj")));
  EXPECT_TRUE(asked_.empty());
}

TEST_F(InputFiles, ProceduralScenesAreNotFiles) {
  ASSERT_TRUE(load_scene("procedural:sphere"));
  EXPECT_TRUE(fetch_scene_file("procedural:sphere"));
  EXPECT_TRUE(asked_.empty());
}

// The viewer's background load: fetched first (where the page may wait), then read without
// asking again.
TEST_F(InputFiles, FetchSceneFileBeforeALoadElsewhere) {
  contents_ = kTriangleObj;
  ASSERT_TRUE(fetch_scene_file(file("early.obj")));
  contents_.clear();
  auto scene = load_scene(file("early.obj"));
  ASSERT_TRUE(scene) << scene.error().message;
  EXPECT_EQ(asked_, std::vector<std::string>{file("early.obj")});
}

TEST_F(InputFiles, TheFetchersErrorIsTheReadersError) {
  auto scene = load_scene(file("missing.obj"));
  ASSERT_FALSE(scene);
  EXPECT_EQ(scene.error().message,
            file("missing.obj") + ": cannot open (fetched http://x/" + file("missing.obj") + ": 404)");
  auto rays = read_rays(file("missing.rays"));
  ASSERT_FALSE(rays);
  EXPECT_NE(rays.error().message.find("missing.rays: cannot open (fetched"), std::string::npos);
}

TEST_F(InputFiles, RaysAnd2dScenesAreFetchedToo) {
  contents_ = "0 0 -1 0 0 1\n";
  auto rays = read_rays(file("later.rays"));
  ASSERT_TRUE(rays) << rays.error().message;
  EXPECT_EQ(rays.value().size(), 1u);
  contents_ = "tri 1 1 3 1 2 3\n";
  auto flat = load_scene(file("later.scene2d"));
  ASSERT_TRUE(flat) << flat.error().message;
  EXPECT_EQ(flat.value().triangle_count(), 1u);
  EXPECT_EQ(asked_, (std::vector<std::string>{file("later.rays"), file("later.scene2d")}));
}

// The viewer's playlists, scripts and bench results: read whole, fetched when missing, the
// fetcher's error as theirs.
TEST_F(InputFiles, ReadInputFileFetchesAMissingFile) {
  contents_ = "state One\n";
  auto text = read_input_file(file("later.playlist"), "the playlist");
  ASSERT_TRUE(text) << text.error().message;
  EXPECT_EQ(text.value(), "state One\n");
  contents_.clear();
  auto missing = read_input_file(file("missing.script"), "the script");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message,
            file("missing.script") + ": cannot open (fetched http://x/" + file("missing.script") + ": 404)");
  EXPECT_EQ(asked_, (std::vector<std::string>{file("later.playlist"), file("missing.script")}));
}

// The page may read its own folder only: an absolute path, or a ".." leading out of the
// working directory, is refused in one line without asking the fetcher.
TEST_F(InputFiles, AbsoluteAndEscapingPathsAreRefusedWithoutAsking) {
  contents_ = kTriangleObj;
  const Status absolute = fetch_missing_input("/nonexistent/accel_input.obj");
  ASSERT_FALSE(absolute);
  EXPECT_EQ(
      absolute.error().message,
      "/nonexistent/accel_input.obj: cannot open (an absolute path; the page reads files of its own folder only)");
  for (const std::string path : {"../accel_outside.obj", "a/../../accel_outside.obj"}) {
    const Status escaping = fetch_missing_input(path);
    ASSERT_FALSE(escaping) << path;
    EXPECT_EQ(escaping.error().message,
              path + ": cannot open (outside the page's folder, which is all the page may read)");
  }
  EXPECT_TRUE(asked_.empty());
  // A ".." that stays inside is a path like any other.
  fs::create_directories("sub");
  EXPECT_TRUE(fetch_missing_input("sub/../inside.obj"));
  EXPECT_EQ(asked_, std::vector<std::string>{"sub/../inside.obj"});
}

TEST(InputFilesNone, WithoutAFetcherAMissingFileIsTheReadersOwnError) {
  set_input_fetcher(nullptr);
  EXPECT_TRUE(fetch_missing_input("/nonexistent/accel_input.obj"));
  auto scene = load_scene("/nonexistent/accel_input.obj");
  ASSERT_FALSE(scene);
  EXPECT_NE(scene.error().message.find("cannot open"), std::string::npos);
  auto text = read_input_file("/nonexistent/accel_input.playlist", "the playlist");
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().message, "/nonexistent/accel_input.playlist: cannot read the playlist");
}

}  // namespace
}  // namespace accel
