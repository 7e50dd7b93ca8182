// OBJ loading (numbering, fan triangulation, every kind of bad input) and procedural scenes.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>

#include <gtest/gtest.h>

#include "ray_gen.h"
#include "scene.h"

namespace accel {
namespace {

namespace fs = std::filesystem;

std::string write_temp(const std::string& name, const std::string& content) {
  const fs::path p = fs::path(::testing::TempDir()) / name;
  std::ofstream(p, std::ios::binary) << content;
  return p.string();
}

std::string shared_scene(const std::string& name) { return std::string(ACCEL_SHARED_SCENES) + "/" + name; }

TEST(ObjLoader, NumbersTrianglesInFileOrderAndFanTriangulates) {
  const std::string path = write_temp("fan.obj",
                                      "# a quad, a triangle and a pentagon\n"
                                      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 3 0 0\nv 3 1 0\n"
                                      "g first\nf 1 2 3 4\n"
                                      "g second\nf 5/1 6/2/3 7//4\n"
                                      "g first\nf 1 2 3 4 5\n");
  auto scene = load_obj(path);
  ASSERT_TRUE(scene) << scene.error().message;
  const auto& t = scene.value().triangles();
  ASSERT_EQ(t.size(), 2u + 1u + 3u);
  EXPECT_EQ(t[0], UVec3(0, 1, 2));  // quad fan (v0,v1,v2),(v0,v2,v3)
  EXPECT_EQ(t[1], UVec3(0, 2, 3));
  EXPECT_EQ(t[2], UVec3(4, 5, 6));  // the triangle, in file order even across groups
  EXPECT_EQ(t[3], UVec3(0, 1, 2));  // pentagon fan
  EXPECT_EQ(t[4], UVec3(0, 2, 3));
  EXPECT_EQ(t[5], UVec3(0, 3, 4));
  EXPECT_EQ(scene.value().vertex_count(), 7u);
}

TEST(ObjLoader, RelativeIndicesAndOddNumbers) {
  const std::string path =
      write_temp("rel.obj", "v 0 0 0\nv +1. 0 0\nv 0 1e0 0\nf -3 -2 -1\nv 2.e0 0 0\nf 2 4 -2\n");
  auto scene = load_obj(path);
  ASSERT_TRUE(scene) << scene.error().message;
  ASSERT_EQ(scene.value().triangle_count(), 2u);
  EXPECT_EQ(scene.value().triangles()[0], UVec3(0, 1, 2));
  EXPECT_EQ(scene.value().triangles()[1], UVec3(1, 3, 2));
  EXPECT_EQ(scene.value().positions()[1], Vec3(1, 0, 0));
}

TEST(ObjLoader, DegenerateTrianglesKeepTheirNumber) {
  auto scene = load_obj(write_temp("deg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 4\nf 1 2 3\n"));
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene.value().triangle_count(), 2u);
  EXPECT_TRUE(scene.value().degenerate(0));
  EXPECT_FALSE(scene.value().degenerate(1));
  EXPECT_EQ(scene.value().valid_prims(), std::vector<uint32_t>{1});
}

struct BadCase {
  const char* name;
  const char* content;
  const char* expected;  // substring of the message, which always starts with "file:line:"
};

class ObjLoaderRejects : public ::testing::TestWithParam<BadCase> {};

TEST_P(ObjLoaderRejects, WithFileAndLine) {
  const BadCase& c = GetParam();
  const std::string path = write_temp(std::string(c.name) + ".obj", c.content);
  auto scene = load_obj(path);
  ASSERT_FALSE(scene);
  const std::string& msg = scene.error().message;
  EXPECT_EQ(msg.rfind(path + ":", 0), 0u) << msg;
  EXPECT_NE(msg.find(c.expected), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
}

INSTANTIATE_TEST_SUITE_P(
    BadInput, ObjLoaderRejects,
    ::testing::Values(BadCase{"nan", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", ":2: vertex coordinate 'nan'"},
                      BadCase{"inf", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", ":3: vertex coordinate 'inf'"},
                      BadCase{"overflow", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", ":2: "},
                      BadCase{"garbage", "v 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n", ":2: malformed number 'x'"},
                      BadCase{"short_vertex", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", ":1: vertex needs 3"},
                      BadCase{"index_zero", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", ":4: face index 0"},
                      BadCase{"index_range", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", ":5: face index 4 out of range"},
                      BadCase{"relative_range", "v 0 0 0\nv 1 0 0\nf 1 2 -3\nv 0 1 0\n", ":3: relative face index -3"},
                      BadCase{"two_corners", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n", ":4: face needs at least 3"},
                      BadCase{"bad_index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 a\n", ":4: malformed face index 'a'"},
                      BadCase{"no_faces", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n", "no triangles"},
                      BadCase{"empty", "", "empty file"},
                      BadCase{"utf16", "\xFE\xFF\0v\0 \0001", "UTF-16"}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

TEST(ObjLoader, RejectsNulBytes) {
  const std::string path = write_temp("nul.obj", std::string("v 0 0 0\nv 1 0\0 0\n", 16));
  auto scene = load_obj(path);
  ASSERT_FALSE(scene);
  EXPECT_NE(scene.error().message.find(path + ":2: not a text file"), std::string::npos) << scene.error().message;
}

TEST(ObjLoader, UnreadableFile) {
  auto scene = load_obj("/nonexistent/dir/scene.obj");
  ASSERT_FALSE(scene);
  EXPECT_NE(scene.error().message.find("/nonexistent/dir/scene.obj: cannot open"), std::string::npos);
  auto dir = load_obj(::testing::TempDir());  // a directory is not a file
  ASSERT_FALSE(dir);
}

// ../shared/scenes/bad/: load what is valid, reject the rest (SOURCES.md says what is odd).
struct SharedBad {
  const char* file;
  int triangles;  // -1: must be rejected
  const char* expected;
};

class SharedBadFiles : public ::testing::TestWithParam<SharedBad> {};

TEST_P(SharedBadFiles, LoadOrReject) {
  const SharedBad& c = GetParam();
  const std::string path = shared_scene(std::string("bad/") + c.file);
  if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
  auto scene = load_obj(path);
  if (c.triangles < 0) {
    ASSERT_FALSE(scene) << c.file << " loaded but should be rejected";
    EXPECT_NE(scene.error().message.find(c.expected), std::string::npos) << scene.error().message;
    EXPECT_EQ(scene.error().message.rfind(path + ":", 0), 0u) << scene.error().message;
  } else {
    ASSERT_TRUE(scene) << scene.error().message;
    EXPECT_EQ(int(scene.value().triangle_count()), c.triangles);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Shared, SharedBadFiles,
    ::testing::Values(SharedBad{"empty.obj", -1, "empty file"},
                      SharedBad{"malformed.obj", -1, "out of range"},
                      SharedBad{"malformed2.obj", -1, "face needs at least 3 vertices"},
                      SharedBad{"number_formats.obj", -1, ":11: malformed number '3.1+e2'"},
                      SharedBad{"concave_polygon.obj", 64, ""},  // one 66-gon, fan = 64 triangles
                      SharedBad{"box_without_lineending.obj", 12, ""},
                      SharedBad{"testline.obj", -1, "no triangles"},
                      SharedBad{"testpoints.obj", -1, "no triangles"},
                      SharedBad{"point_cloud.obj", -1, "no triangles"},
                      SharedBad{"multiple_spaces.obj", 1, ""},
                      SharedBad{"box_UTF16BE.obj", -1, "UTF-16"}),
    [](const auto& param_info) {
      std::string n = param_info.param.file;
      return n.substr(0, n.find('.'));
    });

TEST(ObjLoader, SharedMeshesMatchSourcesTable) {
  // Triangle counts from ../shared/scenes/SOURCES.md.
  const std::pair<const char*, size_t> meshes[] = {{"teapot.obj", 992}, {"spot.obj", 5856}, {"spider.obj", 1368},
                                                   {"cornell_box.obj", 36}, {"holodeck.obj", 4015}};
  for (const auto& [file, count] : meshes) {
    const std::string path = shared_scene(file);
    if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
    auto scene = load_obj(path);
    ASSERT_TRUE(scene) << scene.error().message;
    EXPECT_EQ(scene.value().triangle_count(), count) << file;
  }
}

TEST(Procedural, EveryNamedSceneBuildsAndIsDeterministic) {
  for (const std::string& name : procedural_scene_names()) {
    auto a = make_procedural_scene(name, 5), b = make_procedural_scene(name, 5);
    ASSERT_TRUE(a && b) << name;
    EXPECT_GT(a.value().triangle_count(), 0u) << name;
    EXPECT_EQ(a.value().positions(), b.value().positions()) << name;
    EXPECT_FALSE(procedural_scene_description(name).empty()) << name;
    auto via_spec = load_scene("procedural:" + name);
    ASSERT_TRUE(via_spec) << name;
  }
  auto bad = make_procedural_scene("nope");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("valid:"), std::string::npos);
}

TEST(Procedural, StadiumIsATinyObjectInAHugeRoom) {
  auto s = make_procedural_scene("stadium");
  ASSERT_TRUE(s);
  EXPECT_GT(s.value().bounds().extent().x, 100.0f * 1.0f);  // room ~200 wide, object ~1
  EXPECT_GT(s.value().triangle_count(), 20000u);
}

TEST(Procedural, HugeIsTenMillionTrianglesAndLarge) {
  // Counted, not generated: the 10M-triangle scene takes seconds; the test below runs its
  // generator at a small size.
  EXPECT_EQ(ScatteredSceneSize{}.triangle_count(), 10'000'000u);
  const auto all = procedural_scene_names(true), small = procedural_scene_names();
  EXPECT_NE(std::find(all.begin(), all.end(), "huge"), all.end());
  EXPECT_EQ(std::find(small.begin(), small.end(), "huge"), small.end());
  EXPECT_FALSE(procedural_scene_description("huge").empty());
}

TEST(Procedural, ScatteredSceneIsATerrainWithClosedObjects) {
  ScatteredSceneSize size;
  size.terrain_x = 40;
  size.terrain_z = 25;
  size.boxes = 200;
  size.spheres = {27, 50, 15, 2};
  const Scene a = make_scattered_scene(size, 3), b = make_scattered_scene(size, 3), c = make_scattered_scene(size, 4);
  ASSERT_EQ(a.triangle_count(), size.triangle_count());
  EXPECT_EQ(a.vertex_count(), size.vertex_count());
  EXPECT_EQ(a.degenerate_count(), 0u);
  EXPECT_EQ(a.positions(), b.positions());
  EXPECT_EQ(a.triangles(), b.triangles());
  EXPECT_NE(a.positions(), c.positions());
  EXPECT_EQ(a.name(), "procedural:huge");
  // The terrain spans 200 x 125; objects stand on it and float at most ~30 above it.
  const Aabb& box = a.bounds();
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(box.min[k]) && std::isfinite(box.max[k]));
  EXPECT_GE(box.extent().x, 200.0f);
  EXPECT_LT(box.extent().x, 210.0f);
  EXPECT_GE(box.extent().z, 125.0f);
  EXPECT_LT(box.extent().z, 135.0f);
  EXPECT_LT(box.extent().y, 50.0f);
  // Every object is closed and consistently oriented: each directed edge once, and its
  // reverse once (the terrain, first, is an open sheet).
  const size_t terrain = size_t(2) * size.terrain_x * size.terrain_z;
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (size_t t = terrain; t < a.triangle_count(); ++t) {
    const UVec3& tri = a.triangles()[t];
    for (int k = 0; k < 3; ++k) ++edges[{tri[k], tri[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : edges) {
    ASSERT_EQ(count, 1) << edge.first << "-" << edge.second;
    ASSERT_TRUE(edges.contains({edge.second, edge.first})) << edge.first << "-" << edge.second;
  }
  // ... and faces outwards: each box (12 triangles) and all the spheres enclose a positive volume.
  auto volume = [&](size_t first, size_t count) {
    double v = 0.0;
    for (size_t t = first; t < first + count; ++t) {
      const DVec3 p0(a.vertex(uint32_t(t), 0)), p1(a.vertex(uint32_t(t), 1)), p2(a.vertex(uint32_t(t), 2));
      v += glm::dot(p0, glm::cross(p1, p2)) / 6.0;
    }
    return v;
  };
  for (uint32_t box_index = 0; box_index < size.boxes; ++box_index)
    ASSERT_GT(volume(terrain + 12 * size_t(box_index), 12), 0.0) << "box " << box_index;
  const size_t spheres_first = terrain + 12 * size_t(size.boxes);
  EXPECT_GT(volume(spheres_first, a.triangle_count() - spheres_first), 0.0);
}

}  // namespace
}  // namespace accel

namespace accel {
namespace {

// FNV-1a over the bytes of a vector of plain values.
template <class T>
uint64_t fnv1a(const std::vector<T>& values, uint64_t h = 0xcbf29ce484222325ull) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  for (size_t i = 0; i < values.size() * sizeof(T); ++i) h = (h ^ bytes[i]) * 0x100000001b3ull;
  return h;
}

// The procedural scenes and random rays are the same bits whatever builds them: GCC natively,
// clang in the sanitizer build and in the web page (emscripten, with musl's libm). They were
// not (a call's arguments drawn in either order, sinf's last bit differing between glibc and
// musl). These values are the native build's and the page's alike (checked in both).
TEST(Procedural, ScenesAndRandomRaysAreTheSameBitsForEveryCompiler) {
  const std::map<std::string, std::pair<uint64_t, uint64_t>> expected = {
      // name: {hash of positions and triangles, hash of random:1000:3 rays}
      {"procedural:cornell", {0xe83218efcc74eb73ull, 0x3baba6882ae4b530ull}},
      {"procedural:soup", {0xad27ba7d51c76422ull, 0xfde177c1146b86beull}},
      {"procedural:sphere", {0x4b834b0fd3f94ac9ull, 0x66f5150920fc1eb5ull}},
      {"procedural:stadium", {0x3e9edbaba5548fc4ull, 0xd245f95a738d7529ull}},
      {"procedural:terrain", {0x083b58c908ca521eull, 0xbe338b99eacbc8a0ull}},
  };
  for (const auto& [name, hashes] : expected) {
    auto scene = load_scene(name);
    ASSERT_TRUE(scene) << name;
    const uint64_t geometry = fnv1a(scene.value().triangles(), fnv1a(scene.value().positions()));
    auto rays = make_rays("random:1000:3", scene.value());
    ASSERT_TRUE(rays) << name;
    EXPECT_EQ(geometry, hashes.first) << name;
    EXPECT_EQ(fnv1a(rays.value()), hashes.second) << name;
  }
}

}  // namespace
}  // namespace accel
