// 2D scene files (docs/hits.md, "2D scene files"): parsing, one-line errors naming the line,
// and a save that reads back to the same floats.
#include <filesystem>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "scene2d.h"

namespace accel {
namespace {

TEST(Scene2dFile, ReadsTrianglesInFileOrderInThePlaneZ0) {
  auto scene = parse_scene2d("# a comment\n\ntri 0 0 4 0 0 4\n  tri -1.5 2 0x1p-2 3 5e1 -7  # trailing\n", "b.scene2d");
  // A '#' after the numbers is not a comment: the line has 8 tokens after `tri`.
  ASSERT_FALSE(scene);
  EXPECT_EQ(scene.error().message, "b.scene2d:4: tri needs 6 numbers (x1 y1 x2 y2 x3 y3), got 8");
  scene = parse_scene2d("# a comment\n\ntri 0 0 4 0 0 4\n  tri -1.5 2 0x1p-2 3 5e1 -7\n", "b.scene2d");
  ASSERT_TRUE(scene) << scene.error().message;
  const Scene& s = scene.value();
  EXPECT_TRUE(s.planar());
  ASSERT_EQ(s.triangle_count(), 2u);
  EXPECT_EQ(s.vertex(1, 0), Vec3(-1.5f, 2.0f, 0.0f));
  EXPECT_EQ(s.vertex(1, 1), Vec3(0.25f, 3.0f, 0.0f));
  EXPECT_EQ(s.vertex(1, 2), Vec3(50.0f, -7.0f, 0.0f));
  EXPECT_EQ(s.bounds().min.z, 0.0f);
  EXPECT_EQ(s.bounds().max.z, 0.0f);
}

TEST(Scene2dFile, AnEmptySceneIsValid) {
  auto scene = parse_scene2d("# nothing yet\n", "empty.scene2d");
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene.value().triangle_count(), 0u);
  EXPECT_TRUE(scene.value().planar());
}

TEST(Scene2dFile, BadLinesAreNamedByFileAndLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"tri 0 0 1 0 0 1\nquad 0 0 1 1\n", "s:2: unknown command 'quad' (expected tri x1 y1 x2 y2 x3 y3)"},
      {"seg 0 0 1 1\n", "s:1: 'seg': 2D scenes hold triangles only (a segment has no area: docs/hits.md, 2D scenes)"},
      {"tri 0 0 1 0 0\n", "s:1: tri needs 6 numbers (x1 y1 x2 y2 x3 y3), got 5"},
      {"\n\ntri 0 0 1 0 0 1x\n", "s:3: malformed number '1x' (number 6)"},
      {"tri 0 0 1 inf 0 1\n", "s:1: coordinates must be finite (number 4 is 'inf')"},
      {"tri 0 0 1 nan 0 1\n", "s:1: coordinates must be finite (number 4 is 'nan')"},
      {"tri 0 0 1 0 0 \x01\n", "s:1: malformed number '\\x01' (number 6)"},
  };
  for (const auto& [text, message] : cases) {
    auto scene = parse_scene2d(text, "s");
    ASSERT_FALSE(scene) << text;
    EXPECT_EQ(scene.error().message, message);
  }
}

TEST(Scene2dFile, SavedScenesReadBackToTheSameFloats) {
  std::vector<Vec3> p = {{0.1f, 1e-30f, 0}, {-3.4e38f, 7.0f, 0}, {1.0f / 3.0f, -0.0f, 0}};
  Scene scene(p, {UVec3(0, 1, 2)}, "x");
  ASSERT_TRUE(scene.mark_planar());
  const std::string path = ::testing::TempDir() + "accel_scene2d_" + std::to_string(getpid()) + ".scene2d";
  ASSERT_TRUE(save_scene2d(path, scene));
  auto back = load_scene2d(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(back) << back.error().message;
  ASSERT_EQ(back.value().triangle_count(), 1u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(back.value().vertex(0, k), scene.vertex(0, k)) << k;
  EXPECT_FALSE(load_scene2d(path));  // removed: one line naming it
  EXPECT_EQ(load_scene2d(path).error().message, path + ": cannot open 2D scene for reading");
}

TEST(Scene2dFile, EditsKeepTheSceneTwoDimensional) {
  const Scene scene = parse_scene2d("tri 0 0 1 0 0 1\ntri 2 0 3 0 2 1\n", "s").value();
  const Scene added = scene2d_with_triangle(scene, {5, 5, 6, 5, 5, 6});
  ASSERT_EQ(added.triangle_count(), 3u);
  EXPECT_EQ(added.vertex(2, 1), Vec3(6, 5, 0));
  EXPECT_TRUE(added.planar());
  const Scene moved = scene2d_with_vertex_moved(added, 1, 4, 4);
  EXPECT_EQ(moved.vertex(0, 1), Vec3(4, 4, 0));
  EXPECT_EQ(moved.vertex(1, 0), Vec3(2, 0, 0));
  const Scene removed = scene2d_without_triangle(moved, 0);
  ASSERT_EQ(removed.triangle_count(), 2u);
  EXPECT_EQ(removed.vertex(0, 0), Vec3(2, 0, 0));  // triangle 1 became 0
  EXPECT_TRUE(removed.planar());
  EXPECT_EQ(format_scene2d(removed), "# accelviz 2D scene: tri x1 y1 x2 y2 x3 y3 (docs/hits.md, 2D scene files)\n"
                                     "tri 2 0 3 0 2 1\ntri 5 5 6 5 5 6\n");
}

TEST(Scene2dFile, A2dSceneKeepsItsVerticesInThePlane) {
  Scene scene = parse_scene2d("tri 0 0 1 0 0 1\n", "s").value();
  const std::vector<Vec3> moved = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0.5f}};
  const Status status = scene.move_vertices(moved);
  ASSERT_FALSE(status);
  EXPECT_EQ(status.error().message, "move_vertices: vertex 2 leaves the plane z = 0 of a 2D scene");
  Scene flat({{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {UVec3(0, 1, 2)}, "f");
  EXPECT_EQ(flat.mark_planar().error().message, "2D scene: vertex 0 has z = 1.000000, not 0");
}

}  // namespace
}  // namespace accel
