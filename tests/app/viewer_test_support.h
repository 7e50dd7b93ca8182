#pragma once
// Helpers shared by the viewer's GL-free tests (tests/app/test_*.cpp).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "built_structure.h"
#include "ray_gen.h"
#include "registry.h"
#include "scene.h"

namespace viz::test {

/// A procedural scene, shared as the viewer's jobs take it.
inline std::shared_ptr<const accel::Scene> scene_of(const std::string& name) {
  auto s = accel::make_procedural_scene(name);
  EXPECT_TRUE(s.ok());
  return std::make_shared<const accel::Scene>(std::move(s.value()));
}

/// A ray that hits the procedural sphere off-centre.
inline accel::Ray sphere_ray() {
  accel::Ray r;
  r.org = accel::Vec3(0.13f, 0.21f, 5.0f);
  r.dir = glm::normalize(accel::Vec3(-0.02f, -0.03f, -1.0f));
  return r;
}

/// The build of `request` over `scene` with its steps recorded, as the construction mode
/// records it (accel::build_structure_recorded).
inline accel::Result<accel::RecordedBuild> record_build(const accel::Scene& scene, const StructureRequest& request) {
  auto choice = accel::parse_structure(request.name, request.params);
  if (!choice) return choice.error();
  return accel::build_structure_recorded(*choice.value().info, scene, choice.value().params, request.kernel);
}

}  // namespace viz::test
