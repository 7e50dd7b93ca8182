// The debug ray: build errors, replay after a rebuild, the highlights of a trace step.
#include <gtest/gtest.h>

#include <memory>

#include "built_structure.h"
#include "params.h"
#include "registry.h"
#include "tools/debug_ray.h"
#include "tools/highlights.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

using test::scene_of;
using test::sphere_ray;

// ---------------------------------------------------------------------------------------
// Debug ray: building, replay

TEST(Workbench, BuildErrorsNameTheParameter) {
  auto scene = scene_of("sphere");
  StructureRequest req;
  req.name = "bvh";
  req.params = {"leaf_size=500"};
  auto built = build_structure_now(scene, req);
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.error().message.find("leaf_size"), std::string::npos);
  req.name = "nope";
  req.params = {};
  EXPECT_FALSE(build_structure_now(scene, req).ok());
  EXPECT_EQ(accel::with_param({"a=1", "b=2"}, "b", "3"), (std::vector<std::string>{"a=1", "b=3"}));
  EXPECT_EQ(accel::with_param({"a=1"}, "c", "x"), (std::vector<std::string>{"a=1", "c=x"}));
  EXPECT_EQ(accel::param_value({"a=1", "traversal=dfs"}, "traversal"), "dfs");
  EXPECT_EQ(accel::param_value({"a=1"}, "traversal", "ordered"), "ordered");
}

TEST(Workbench, RayReplayAfterRebuildKeepsTheStep) {
  auto scene = scene_of("sphere");
  StructureRequest req;
  req.name = "bvh";
  req.params = {"leaf_size=16"};
  auto coarse = build_structure_now(scene, req);
  req.params = {"leaf_size=1", "traversal=pqueue"};
  auto fine = build_structure_now(scene, req);
  ASSERT_TRUE(coarse.ok() && fine.ok());
  DebugRay ray;
  ray.active = true;
  ray.ray = sphere_ray();
  ray.record(*coarse.value()->structure, false);
  ASSERT_TRUE(ray.hit.valid());
  const accel::Hit first = ray.hit;
  ray.player.jump_to_end();
  const size_t old_step = ray.player.step();
  ray.record(*fine.value()->structure, true);  // the rebuild
  EXPECT_EQ(ray.hit.prim, first.prim);
  EXPECT_EQ(ray.hit.t, first.t);
  EXPECT_EQ(ray.player.step(), std::min(old_step, ray.player.size() - 1));
  ray.player.seek(3);
  ray.record(*coarse.value()->structure, true);
  EXPECT_EQ(ray.player.step(), 3u);
  ray.record(*coarse.value()->structure, false);  // a new ray starts over
  EXPECT_EQ(ray.player.step(), 0u);
  EXPECT_NEAR(ray_draw_length(ray.ray, ray.hit, scene->bounds()), ray.hit.t, 0.0f);
  accel::Hit none;
  EXPECT_GT(ray_draw_length(ray.ray, none, scene->bounds()), 5.0f);  // through the whole box
}

// ---------------------------------------------------------------------------------------
// Highlights of the current step (GL-free: what the ray debugger uploads)

TEST(Highlights, FollowTheTraceStep) {
  auto scene = scene_of("sphere");
  StructureRequest req;
  req.name = "bvh";
  req.params = {"traversal=pqueue"};
  auto built = build_structure_now(scene, req);
  ASSERT_TRUE(built.ok()) << built.error().message;
  DebugRay ray;
  EXPECT_TRUE(build_highlights(ray, *scene, built.value().get(), {}).segments.empty());  // no ray: nothing

  ray.active = true;
  ray.ray = sphere_ray();
  ray.record(*built.value()->structure, false);
  ASSERT_TRUE(ray.hit.valid());
  ASSERT_GT(ray.player.size(), 3u);

  // First step: the ray and the root node, its pseudo-code line known.
  ray.player.seek(0);
  const Highlights first = build_highlights(ray, *scene, built.value().get(), {});
  EXPECT_FALSE(first.segments.empty());
  EXPECT_GE(first.code_line, 0);
  EXPECT_EQ(first.step.event.kind, ray.player.events()[0].kind);

  // Last step: the closest hit is known and drawn (a filled triangle and the hit marker).
  ray.player.jump_to_end();
  const Highlights last = build_highlights(ray, *scene, built.value().get(), {});
  EXPECT_EQ(last.step.closest_prim, ray.hit.prim);
  EXPECT_GE(last.triangles.size(), 3u);
  EXPECT_GT(last.segments.size(), first.segments.size());

  // Trail, skipped and pending nodes are thin lines, off when unticked.
  const Highlights none = build_highlights(ray, *scene, built.value().get(), {false, false, false});
  EXPECT_LE(none.lines.size(), last.lines.size());
  EXPECT_TRUE(none.lines.empty());

  // Without a structure for the scene: only the ray and its hit.
  const Highlights bare = build_highlights(ray, *scene, nullptr, {});
  EXPECT_EQ(bare.code_line, -1);
  EXPECT_EQ(bare.triangles.size(), 3u);
}

}  // namespace
}  // namespace viz
