// The blackboard's (2D mode's) own views (issue #50): a sphere-tree node is one circle in the
// plane z = 0 wherever the viewer draws it (node instances, the debug ray's highlights, the
// construction), the panels' and the help's mouse texts are the blackboard's in 2D, and the
// octree's 2D defaults subdivide the lecture's ten triangles.
#include <gtest/gtest.h>

#include <string>

#include "built_structure.h"
#include "commands.h"
#include "input.h"
#include "scene2d.h"
#include "structure_view.h"
#include "tools/build_playback.h"
#include "tools/highlights.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

/// The lecture's ten triangles (scenes/blackboard.scene2d), planar.
std::shared_ptr<const accel::Scene> blackboard() {
  auto scene = accel::load_scene2d(std::string(ACCEL_SOURCE_DIR) + "/scenes/blackboard.scene2d");
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_TRUE(scene.value().planar());
  return std::make_shared<const accel::Scene>(std::move(scene.value()));
}

BuiltPtr build(std::shared_ptr<const accel::Scene> scene, const std::string& name) {
  StructureRequest request;
  request.name = name;
  auto built = build_structure_now(std::move(scene), request);
  EXPECT_TRUE(built.ok()) << built.error().message;
  return built.value();
}

/// A line list (vertex pairs) is one closed loop: every segment starts where the one before
/// it ended, and the last ends where the first started.
void expect_one_closed_loop(const std::vector<glm::vec3>& lines) {
  ASSERT_GE(lines.size(), 6u);
  ASSERT_EQ(lines.size() % 2, 0u);
  for (size_t i = 2; i < lines.size(); i += 2) EXPECT_EQ(lines[i], lines[i - 1]) << i;
  EXPECT_NEAR(glm::length(lines.back() - lines.front()), 0.0f, 1e-5f);
}

// ---------------------------------------------------------------------------------------
// Sphere-tree nodes: one circle in 2D, three great circles in 3D

TEST(Blackboard2d, SphereNodeIsOneClosedCircleInThePlane) {
  const glm::vec3 c(3.0f, 4.0f, 0.0f);
  const float r = 2.0f;
  const std::vector<glm::vec3> flat = sphere_outline(c, r, true, 32);
  ASSERT_EQ(flat.size(), 2u * 32u);  // 32 segments: one circle, no cross inside it
  for (const glm::vec3& p : flat) {
    EXPECT_EQ(p.z, 0.0f);
    EXPECT_NEAR(glm::length(p - c), r, 1e-5f);
  }
  expect_one_closed_loop(flat);
  // 3D keeps its three great circles, two of them across the plane.
  const std::vector<glm::vec3> round = sphere_outline(c, r, false, 32);
  EXPECT_EQ(round.size(), 3u * 2u * 32u);
  size_t off_plane = 0;
  for (const glm::vec3& p : round) off_plane += p.z != 0.0f;
  EXPECT_GT(off_plane, 32u);
  // A centre off the plane: the circle where the sphere cuts it; none when it misses it.
  glm::vec3 centre;
  float radius = 0.0f;
  ASSERT_TRUE(sphere_in_plane({1.0f, 2.0f, 3.0f}, 5.0f, &centre, &radius));
  EXPECT_EQ(centre, glm::vec3(1.0f, 2.0f, 0.0f));
  EXPECT_FLOAT_EQ(radius, 4.0f);
  EXPECT_FALSE(sphere_in_plane({0.0f, 0.0f, 6.0f}, 5.0f, &centre, &radius));
  EXPECT_TRUE(sphere_outline({0.0f, 0.0f, 6.0f}, 5.0f, true).empty());
  // The thick outline of a node (current node, selection) is that circle too.
  accel::NodeView v;
  v.id = 0;
  v.sphere.center = c;
  v.sphere.radius = r;
  std::vector<Segment> thick;
  append_node_segments(thick, v, glm::vec4(1.0f), 3.0f, true);
  ASSERT_EQ(thick.size(), 48u);
  std::vector<glm::vec3> ends;
  for (const Segment& s : thick) ends.insert(ends.end(), {s.a, s.b});
  for (const glm::vec3& p : ends) EXPECT_EQ(p.z, 0.0f);
  expect_one_closed_loop(ends);
  std::vector<ColorVertex> thin;
  append_node_lines(thin, v, glm::vec4(1.0f), true);
  EXPECT_EQ(thin.size(), 2u * 32u);
}

TEST(Blackboard2d, SphereTreeInstancesAreTheirCircles) {
  const BuiltPtr built = build(blackboard(), "spheretree");
  ASSERT_TRUE(built);
  const StructureGeometry& g = built->geometry;
  EXPECT_TRUE(g.planar);  // drawn with the one-circle unit shape
  ASSERT_EQ(g.spheres.size(), g.nodes);
  size_t i = 0;
  built->structure->for_each_node([&](const accel::NodeView& v) {
    ASSERT_LT(i, g.spheres.size());
    const NodeInstance& n = g.spheres[i++];
    EXPECT_EQ(n.lo.z, 0.0f);
    EXPECT_EQ(glm::vec2(n.lo), glm::vec2(v.sphere.center));
    EXPECT_FLOAT_EQ(n.hi.x, v.sphere.radius);  // the sphere tree's centres lie in the plane
  });
  // The unit shape of one circle lies in z = 0, and a 3D scene's spheres stay spheres.
  for (const glm::vec3& p : unit_circle(24)) EXPECT_EQ(p.z, 0.0f);
  EXPECT_EQ(unit_circle(24).size(), 48u);
  EXPECT_FALSE(build(test::scene_of("sphere"), "spheretree")->geometry.planar);
}

TEST(Blackboard2d, HighlightsAndConstructionStayInThePlane) {
  const auto scene = blackboard();
  const BuiltPtr built = build(scene, "spheretree");
  ASSERT_TRUE(built);
  DebugRay ray;
  ray.active = true;
  ray.ray.org = accel::Vec3(0.5f, 4.2f, 0.0f);  // the lecture's ray (scenes/lecture.playlist)
  ray.ray.dir = accel::Vec3(1.0f, 0.1f, 0.0f);
  ray.record(*built->structure, false, scene.get());
  ASSERT_TRUE(ray.hit.valid());
  size_t circles = 0;
  for (size_t step = 0; step < ray.player.size(); ++step) {
    ray.player.seek(step);
    const Highlights h = build_highlights(ray, *scene, built.get(), {});
    // Everything on the board lies in its plane: a great circle across it would not.
    for (const Segment& s : h.segments) {
      EXPECT_EQ(s.a.z, 0.0f) << "step " << step;
      EXPECT_EQ(s.b.z, 0.0f) << "step " << step;
    }
    for (const ColorVertex& v : h.lines) EXPECT_EQ(v.position.z, 0.0f) << "step " << step;
    circles += h.lines.size();
  }
  EXPECT_GT(circles, 0u);  // trail, skipped and pending circles were drawn

  StructureRequest request;
  request.name = "spheretree";
  auto rec = test::record_build(*scene, request);
  ASSERT_TRUE(rec.ok()) << rec.error().message;
  accel::BuildReplay replay(rec.value().trace);
  for (size_t step = 0; step <= rec.value().trace.events.size(); ++step) {
    replay.seek(step);
    const BuildView v = build_view(rec.value().trace, replay, *scene);
    for (const ColorVertex& p : v.lines) EXPECT_EQ(p.position.z, 0.0f) << "build step " << step;
    for (const Segment& s : v.segments) EXPECT_EQ(s.a.z, 0.0f) << "build step " << step;
  }
}

// ---------------------------------------------------------------------------------------
// The mouse's texts: the blackboard's in 2D

TEST(Blackboard2d, MouseTextsSayWhatTheBoardDoes) {
  auto joined = [](const std::vector<std::string>& lines) {
    std::string all;
    for (const std::string& l : lines) all += l + "\n";
    return all;
  };
  const std::string board = joined(mouse_help_lines(true)), view = joined(mouse_help_lines(false));
  // 2D: clicks place corners, a drag shoots the ray or moves a corner, a right click deletes.
  EXPECT_NE(board.find("left click: place a triangle's corner"), std::string::npos) << board;
  EXPECT_NE(board.find("left drag: from a corner: move it"), std::string::npos) << board;
  EXPECT_NE(board.find("shoot the debug ray from where the drag starts"), std::string::npos) << board;
  EXPECT_NE(board.find("right click: delete the triangle"), std::string::npos) << board;
  EXPECT_EQ(board.find("orbit"), std::string::npos) << board;
  EXPECT_EQ(board.find("saved viewpoint"), std::string::npos) << board;  // no click shoots there
  // 3D: a drag orbits, a click shoots.
  EXPECT_NE(view.find("left drag: orbit the camera"), std::string::npos) << view;
  EXPECT_NE(view.find("left click: shoot the debug ray through that pixel"), std::string::npos) << view;
  EXPECT_EQ(view.find("triangle"), std::string::npos) << view;
  // The panels waiting for a ray.
  EXPECT_NE(std::string(shoot_hint(true)).find("drag on the board"), std::string::npos);
  EXPECT_EQ(std::string(shoot_hint(true)).find("click"), std::string::npos);
  EXPECT_NE(std::string(shoot_hint(false)).find("click into the scene"), std::string::npos);
  // The docs' table: one row per action, both modes, a dash where it does nothing.
  const std::string table = mouse_markdown();
  EXPECT_EQ(table.rfind("| mouse | 3D view | blackboard (2D mode) |\n|---|---|---|\n", 0), 0u);
  size_t rows = 0;
  for (char ch : table) rows += ch == '\n';
  EXPECT_EQ(rows, 2 + mouse_rows().size());
  EXPECT_NE(table.find("| right click | \u2014 | delete the triangle under the cursor |"), std::string::npos) << table;
}

// ---------------------------------------------------------------------------------------
// The octree's 2D defaults

TEST(Blackboard2d, OctreeDefaultsSubdivideTheBoard) {
  const BuiltPtr built = build(blackboard(), "octree");
  ASSERT_TRUE(built);
  EXPECT_GT(built->stats.leaves, 1u);  // not one no-gain leaf (the 3D defaults' answer)
  EXPECT_GT(built->geometry.nodes, 5u);
  // The parameters in use, as the Structure section lists them.
  EXPECT_NE(built->params_text.find("max_prims=1 "), std::string::npos) << built->params_text;
  EXPECT_NE(built->params_text.find("ct=0"), std::string::npos) << built->params_text;
  // In 3D the octree's defaults are as before.
  const BuiltPtr solid = build(test::scene_of("sphere"), "octree");
  ASSERT_TRUE(solid);
  EXPECT_NE(solid->params_text.find("max_prims=8 "), std::string::npos) << solid->params_text;
  EXPECT_NE(solid->params_text.find("ct=2"), std::string::npos) << solid->params_text;
}

}  // namespace
}  // namespace viz
