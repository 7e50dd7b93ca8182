// The camera model behind picking: the pixel ray round trip and saved views.
#include <gtest/gtest.h>

#include <cmath>

#include "camera.h"
#include "viewer_test_support.h"

namespace viz {
namespace {


// ---------------------------------------------------------------------------------------
// Camera model: picking equals rendering

TEST(CameraModel, PixelRayRoundTrip) {
  Camera cam;
  accel::Aabb box;
  box.min = glm::vec3(-1.0f, 0.0f, -1.0f);
  box.max = glm::vec3(1.0f, 2.0f, 1.0f);
  const int w = 1280, h = 720;
  cam.frame(box, float(w) / float(h));
  cam.orbit(37.0f, -12.0f);
  const accel::PinholeCamera pin = cam.pinhole();
  EXPECT_NEAR(glm::length(pin.eye - cam.eye()), 0.0f, 1e-5f);
  for (const glm::vec2 px : {glm::vec2(0.5f, 0.5f), glm::vec2(640.0f, 360.0f), glm::vec2(1200.25f, 33.75f),
                             glm::vec2(17.0f, 700.0f)}) {
    const accel::Ray ray = accel::camera_ray(pin, px.x, px.y, w, h);
    for (float t : {1.0f, 3.0f, 7.5f}) {
      // The rendered position of a point on the ray is the pixel the ray was shot through.
      const glm::vec3 p = cam.project(ray.at(t), w, h);
      EXPECT_NEAR(p.x, px.x, 0.05f) << px.x << "," << px.y << " t=" << t;
      EXPECT_NEAR(p.y, px.y, 0.05f) << px.x << "," << px.y << " t=" << t;
    }
  }
  // The centre pixel's ray is the view direction.
  const accel::Ray centre = accel::camera_ray(pin, 0.5f * w, 0.5f * h, w, h);
  EXPECT_NEAR(glm::dot(centre.dir, glm::normalize(cam.target() - cam.eye())), 1.0f, 1e-5f);
}

TEST(CameraModel, LookAtReproducesTheView) {
  Camera cam;
  accel::Aabb box;
  box.min = glm::vec3(-100.0f);
  box.max = glm::vec3(100.0f);
  cam.look_at({2.4f, 1.7f, 3.2f}, {0.0f, 0.45f, 0.0f}, 40.0f, box);
  const accel::PinholeCamera pin = cam.pinhole();
  EXPECT_NEAR(glm::length(pin.eye - glm::vec3(2.4f, 1.7f, 3.2f)), 0.0f, 1e-4f);
  EXPECT_NEAR(glm::length(pin.target - glm::vec3(0.0f, 0.45f, 0.0f)), 0.0f, 1e-6f);
  EXPECT_NEAR(pin.fovy_deg, 40.0f, 1e-4f);
  // The target projects to the image centre.
  const glm::vec3 c = cam.project(pin.target, 800, 600);
  EXPECT_NEAR(c.x, 400.0f, 0.01f);
  EXPECT_NEAR(c.y, 300.0f, 0.01f);
}

}  // namespace
}  // namespace viz
