// The window layout, the 3D view's rectangle between the docked panels, framing the scene
// into it, and what the scene combo shows for the loaded scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "camera.h"
#include "presets.h"
#include "view_layout.h"

namespace viz {
namespace {

/// The docked edges of the default layout at `display` with font size `em`.
DockEdges docked(glm::vec2 display, float em) {
  const PanelLayout l = compute_layout(display, em, /*lecture=*/false, /*main_open=*/true);
  DockEdges d{0.0f, display.x};
  for (const WindowRect* w : {&l.main, &l.ray, &l.code, &l.steps}) note_docked(d, display.x, w->pos, w->size);
  return d;
}

TEST(ViewLayout, TheCompareTableNeverCoversTheVariables) {
  for (glm::vec2 display : {glm::vec2(1280, 720), glm::vec2(1600, 900), glm::vec2(1920, 1080)})
    for (bool lecture : {false, true}) {
      const float em = lecture ? 30.0f : 16.0f;
      const PanelLayout l = compute_layout(display, em, lecture, /*main_open=*/true);
      EXPECT_GE(l.bottom.pos.x, l.vars.pos.x + l.vars.size.x) << display.x << "x" << display.y;
      EXPECT_LE(l.bottom.pos.x + l.bottom.size.x, display.x);
    }
}

TEST(ViewLayout, VariablesSitUnderTheControlsInTheLeftColumn) {
  const glm::vec2 display(1600, 900);
  for (bool lecture : {false, true}) {
    const float em = lecture ? 30.0f : 18.0f;
    const PanelLayout l = compute_layout(display, em, lecture, /*main_open=*/true);
    EXPECT_EQ(l.vars.pos.x, l.main.pos.x);
    EXPECT_EQ(l.vars.size.x, l.main.size.x);
    EXPECT_NEAR(l.vars.pos.y + l.vars.size.y, display.y - 0.4f * em, 0.5f) << "down to the bottom edge";
    if (lecture) {
      // The controls collapse to their title bar: the variables take the column.
      EXPECT_LT(l.vars.pos.y, 3.0f * em);
    } else {
      EXPECT_GE(l.vars.pos.y, l.main.pos.y + l.main.size.y) << "below the controls, not over them";
      EXPECT_GT(l.vars.size.y, 0.3f * display.y);
    }
  }
}

TEST(ViewLayout, DefaultWindowLeavesTheMiddleFree) {
  // 1280x720 at the viewer's 18 px font: the view lies between the controls and the debug
  // ray panels (it used to fall back to the whole window, leaving the mesh under them).
  const glm::vec2 display(1280, 720);
  const DockEdges d = docked(display, 18.0f);
  const glm::ivec4 v = view_rect(d, display, {1, 1}, true);
  EXPECT_NEAR(v.x, d.left, 1.0);
  EXPECT_NEAR(v.x + v.z, d.right, 1.0);
  EXPECT_LT(v.z, 640);
  EXPECT_GT(v.z, 320);
  EXPECT_EQ(v.w, 720);
  // Hidden panels: the whole window.
  EXPECT_EQ(view_rect(d, display, {1, 1}, false), glm::ivec4(0, 0, 1280, 720));
  // HiDPI: framebuffer pixels.
  const glm::ivec4 hi = view_rect(d, display, {2, 2}, true);
  EXPECT_NEAR(hi.x, 2 * v.x, 1.0);
  EXPECT_EQ(hi.w, 1440);
}

TEST(ViewLayout, SmallWindowsUseTheWholeWidth) {
  // 640x360 (the screenshot tests): between the panels would be a sliver; panels over the
  // scene are better then.
  const glm::vec2 display(640, 360);
  EXPECT_EQ(view_rect(docked(display, 18.0f), display, {1, 1}, true), glm::ivec4(0, 0, 640, 360));
}

TEST(ViewLayout, TheTreeDiagramDocksAlongTheBottom) {
  // The tree goes under the 3D view, between the columns; the view ends above it.
  const glm::vec2 display(1920, 1080);
  const PanelLayout l = compute_layout(display, 18.0f, false, true);
  DockEdges d = docked(display, 18.0f);
  EXPECT_GE(l.tree.pos.x, d.left);
  EXPECT_LE(l.tree.pos.x + l.tree.size.x, d.right);
  EXPECT_NEAR(l.tree.pos.y + l.tree.size.y, display.y, 0.01f * display.y);
  note_docked_bottom(d, display.y, l.tree.pos, l.tree.size);
  EXPECT_FLOAT_EQ(d.bottom, l.tree.pos.y);
  const glm::ivec4 v = view_rect(d, display, {1, 1}, true);
  EXPECT_EQ(v.y, 0);
  EXPECT_NEAR(v.w, l.tree.pos.y, 1.0);
  EXPECT_GT(v.w, 540);  // the scene keeps most of the height
  // Hidden panels: the whole window again; HiDPI: framebuffer pixels.
  EXPECT_EQ(view_rect(d, display, {1, 1}, false).w, 1080);
  EXPECT_NEAR(view_rect(d, display, {2, 2}, true).w, 2.0f * l.tree.pos.y, 1.0);
  // A window in the upper half, or one not reaching the bottom, is no bottom dock.
  DockEdges top = docked(display, 18.0f);
  note_docked_bottom(top, display.y, {600, 100}, {400, 300});
  note_docked_bottom(top, display.y, {600, 700}, {400, 100});
  EXPECT_EQ(top.bottom, 0.0f);
  // In lecture mode it is still below the view, taller.
  const PanelLayout big = compute_layout(display, 30.0f, true, true);
  EXPECT_GT(big.tree.size.y, l.tree.size.y);
  EXPECT_NEAR(big.tree.pos.y + big.tree.size.y, display.y, 0.02f * display.y);
}

TEST(ViewLayout, FramingFitsTheSceneIntoTheViewRectangle) {
  const glm::vec2 display(1280, 720);
  const glm::ivec4 v = view_rect(docked(display, 18.0f), display, {1, 1}, true);
  accel::Aabb box;  // bunny-sized
  box.extend(glm::vec3(-0.1f, 0.0f, -0.08f));
  box.extend(glm::vec3(0.06f, 0.15f, 0.05f));
  Camera c;
  c.frame(box, static_cast<float>(v.z) / static_cast<float>(v.w));
  // Every corner projects inside the view (camera pixels are relative to the view).
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 p((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y, (i & 4) ? box.max.z : box.min.z);
    const glm::vec3 q = c.project(p, v.z, v.w);
    EXPECT_GE(q.x, 0.0f);
    EXPECT_LE(q.x, static_cast<float>(v.z));
    EXPECT_GE(q.y, 0.0f);
    EXPECT_LE(q.y, static_cast<float>(v.w));
  }
}

TEST(SceneLabel, ShowsTheLoadedSceneNotTheFirstPreset) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "accelviz_scene_label";
  std::filesystem::create_directories(dir / "sub");
  const std::filesystem::path obj = dir / "sub" / "bunny.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::vector<Preset> presets(2);
  presets[0].name = "cornell";
  presets[0].scene = "procedural:cornell";
  presets[1].name = "bunny";
  presets[1].scene = obj.string();
  EXPECT_EQ(preset_for_scene(presets, "procedural:cornell"), 0);
  // The same file under another spelling of its path is that preset.
  EXPECT_EQ(preset_for_scene(presets, (dir / "sub" / ".." / "sub" / "bunny.obj").string()), 1);
  EXPECT_EQ(preset_for_scene(presets, "procedural:sphere"), -1);
  EXPECT_EQ(preset_for_scene(presets, (dir / "other.obj").string()), -1);
  EXPECT_EQ(scene_label("../shared/scenes/dragon.obj"), "dragon.obj");
  EXPECT_EQ(scene_label("procedural:soup"), "soup");
  EXPECT_EQ(scene_label("dir/"), "(file)");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace viz
