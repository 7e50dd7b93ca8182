// The blackboard's mouse (2D mode): the top-down camera's pixel <-> plane mapping, three
// clicks make a triangle, a drag shoots a ray, and the grid's spacing.
#include <gtest/gtest.h>

#include "camera.h"
#include "input.h"
#include "tools/blackboard_editor.h"

namespace viz {
namespace {

TEST(BlackboardCamera, PlanePointsAndProjectionAgree) {
  Camera cam;
  cam.set_top_down(true);
  cam.frame(accel::Aabb{accel::Vec3(0.0f), accel::Vec3(10.0f, 10.0f, 0.0f)}, 640.0f / 480.0f);
  // The board's centre is the view's centre; +Y is up on the screen.
  const glm::vec3 centre = cam.plane_point(320.0f, 240.0f, 640, 480);
  EXPECT_NEAR(centre.x, 5.0f, 1e-5f);
  EXPECT_NEAR(centre.y, 5.0f, 1e-5f);
  EXPECT_EQ(centre.z, 0.0f);
  EXPECT_GT(cam.plane_point(320.0f, 100.0f, 640, 480).y, 5.0f);
  // What is drawn at a pixel is the plane point picked there.
  for (glm::vec2 px : {glm::vec2(10, 20), glm::vec2(600, 470), glm::vec2(320.5f, 0.5f)}) {
    const glm::vec3 p = cam.plane_point(px.x, px.y, 640, 480);
    const glm::vec3 back = cam.project(p, 640, 480);
    EXPECT_NEAR(back.x, px.x, 1e-3f);
    EXPECT_NEAR(back.y, px.y, 1e-3f);
  }
  // The pinhole camera (the heat map's rays) meets the plane where the view draws it.
  for (glm::vec2 px : {glm::vec2(10.5f, 20.5f), glm::vec2(600.5f, 470.5f)}) {
    const accel::Ray ray = accel::camera_ray(cam.pinhole(), px.x, px.y, 640, 480);
    const float t = -ray.org.z / ray.dir.z;
    const glm::vec3 hit = ray.org + t * ray.dir, drawn = cam.plane_point(px.x, px.y, 640, 480);
    EXPECT_NEAR(hit.x, drawn.x, 1e-3f);
    EXPECT_NEAR(hit.y, drawn.y, 1e-3f);
  }
  // Orbiting does nothing; zooming in shrinks the world per pixel.
  const float before = cam.units_per_pixel(480.0f);
  cam.orbit(100.0f, 50.0f);
  EXPECT_EQ(cam.plane_point(320.0f, 240.0f, 640, 480), centre);
  cam.zoom(1.0f);
  EXPECT_LT(cam.units_per_pixel(480.0f), before);
}

ClickResult click_at(glm::vec2 pos) {
  ClickResult r;
  r.click = true;
  r.press_pos = pos;
  r.pos = pos;
  return r;
}

TEST(BlackboardEditor, ThreeClicksAddATriangle) {
  BlackboardEditor e;
  EXPECT_EQ(e.update(click_at({0, 0}), {1, 2}, {1, 2}, false).kind, BlackboardAction::Kind::None);
  EXPECT_EQ(e.update(ClickResult{}, {}, {}, false).kind, BlackboardAction::Kind::None);  // no button: nothing
  EXPECT_EQ(e.update(click_at({0, 0}), {3, 2}, {3, 2}, false).kind, BlackboardAction::Kind::None);
  EXPECT_EQ(e.pending().size(), 2u);
  const BlackboardAction a = e.update(click_at({0, 0}), {1, 4}, {1, 4}, false);
  ASSERT_EQ(a.kind, BlackboardAction::Kind::AddTriangle);
  EXPECT_EQ(a.triangle, (std::array<float, 6>{1, 2, 3, 2, 1, 4}));
  EXPECT_TRUE(e.pending().empty());
}

TEST(BlackboardEditor, ADragShootsTheRayAlongIt) {
  BlackboardEditor e;
  ClickResult held;
  EXPECT_EQ(e.update(held, {1, 1}, {4, 5}, true).kind, BlackboardAction::Kind::None);
  ASSERT_TRUE(e.drag_line().has_value());
  EXPECT_EQ(e.drag_line()->second, glm::vec2(4, 5));
  ClickResult released;
  released.drag_end = true;
  const BlackboardAction a = e.update(released, {1, 1}, {4, 5}, false);
  ASSERT_EQ(a.kind, BlackboardAction::Kind::ShootRay);
  EXPECT_EQ(a.ray.org, accel::Vec3(1, 1, 0));
  EXPECT_EQ(a.ray.dir, accel::Vec3(3, 4, 0));
  EXPECT_FALSE(e.drag_line().has_value());
  EXPECT_TRUE(e.pending().empty());  // a drag places no corner
}

TEST(BlackboardEditor, ADragFromACornerMovesItFrameByFrame) {
  BlackboardEditor e;
  ClickResult held;
  // The first frame of the drag grabs vertex 7 (found at the press point by App).
  BlackboardAction a = e.update(held, {1, 1}, {2, 1}, true, 7);
  ASSERT_EQ(a.kind, BlackboardAction::Kind::MoveVertex);
  EXPECT_EQ(a.vertex, 7);
  EXPECT_EQ(a.position, glm::vec2(2, 1));
  EXPECT_FALSE(e.drag_line().has_value());  // no ray is being dragged
  // It keeps it, whatever lies under the cursor now, until the release.
  a = e.update(held, {1, 1}, {3, 2}, true, -1);
  EXPECT_EQ(a.vertex, 7);
  ClickResult released;
  released.drag_end = true;
  a = e.update(released, {1, 1}, {3, 3}, false, -1);
  ASSERT_EQ(a.kind, BlackboardAction::Kind::MoveVertex);
  EXPECT_EQ(a.position, glm::vec2(3, 3));
  // The next drag from empty space shoots a ray again.
  e.update(held, {5, 5}, {6, 5}, true, -1);
  EXPECT_EQ(e.update(released, {5, 5}, {6, 5}, false, -1).kind, BlackboardAction::Kind::ShootRay);
}

TEST(BlackboardEditor, GridLinesAreOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_FLOAT_EQ(grid_spacing(0.01f, 24.0f), 0.5f);   // 0.24 wanted
  EXPECT_FLOAT_EQ(grid_spacing(0.05f, 24.0f), 2.0f);   // 1.2
  EXPECT_FLOAT_EQ(grid_spacing(0.1f, 20.0f), 2.0f);    // 2.0 exactly
  EXPECT_FLOAT_EQ(grid_spacing(3.0f, 24.0f), 100.0f);  // 72
}

}  // namespace
}  // namespace viz
