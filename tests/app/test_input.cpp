// Click vs drag (ClickTracker): judged by the press and release positions and times, never
// by mouse deltas, so a slow frame cannot turn a click into an orbit.
#include <gtest/gtest.h>

#include "input.h"

namespace viz {
namespace {

TEST(ClickTracker, SlowFramePressIsStillAClick) {
  ClickTracker t;
  // Frame 1 (t = 0): the cursor rests over a panel edge, button up.
  EXPECT_FALSE(t.update(false, {100, 100}, 0.0, true).click);
  // Frame 2 (t = 0.5 s, 2 fps): in one frame the cursor moved 300 px onto the mesh and
  // the button went down. That movement happened before the press.
  ClickResult r = t.update(true, {400, 300}, 0.5, true);
  EXPECT_FALSE(r.click);
  EXPECT_EQ(r.orbit, glm::vec2(0.0f));
  EXPECT_TRUE(t.held());
  EXPECT_FALSE(t.dragging());
  // Frame 3 (t = 1.0 s): released where it was pressed: a click at the press position.
  r = t.update(false, {400, 300}, 1.0, true);
  EXPECT_TRUE(r.click);
  EXPECT_EQ(r.orbit, glm::vec2(0.0f));
  EXPECT_EQ(r.press_pos, glm::vec2(400, 300));
  EXPECT_FALSE(t.held());
}

TEST(ClickTracker, RealDragOrbitsAndIsNoClick) {
  ClickTracker t;
  t.update(false, {400, 300}, 0.0, true);
  t.update(true, {400, 300}, 0.1, true);
  // Within the tolerance: no orbit yet (a shaky click must not turn the view).
  ClickResult r = t.update(true, {402, 301}, 0.2, true);
  EXPECT_EQ(r.orbit, glm::vec2(0.0f));
  EXPECT_FALSE(t.dragging());
  // Beyond it: the orbit covers the whole way from the press, then frame to frame.
  r = t.update(true, {420, 310}, 0.3, true);
  EXPECT_TRUE(t.dragging());
  EXPECT_EQ(r.orbit, glm::vec2(20, 10));
  r = t.update(true, {425, 310}, 0.4, true);
  EXPECT_EQ(r.orbit, glm::vec2(5, 0));
  // Back at the press position and released: still a drag, so no ray.
  r = t.update(false, {400, 300}, 0.5, true);
  EXPECT_FALSE(r.click);
  EXPECT_FALSE(t.dragging());
}

TEST(ClickTracker, PressOverAPanelAndLongHoldsAreNoClicks) {
  ClickTracker t;
  t.update(true, {10, 10}, 0.0, /*press_allowed=*/false);  // ImGui wants the mouse
  EXPECT_FALSE(t.held());
  EXPECT_FALSE(t.update(false, {10, 10}, 0.1, true).click);

  t.update(true, {300, 300}, 1.0, true);
  const ClickResult r = t.update(false, {300, 300}, 1.0 + ClickTracker::kMaxClickSeconds + 0.5, true);
  EXPECT_FALSE(r.click);
}

TEST(ClickTracker, ReleaseJustInsideTheToleranceIsAClick) {
  ClickTracker t;
  t.update(true, {300, 300}, 0.0, true);
  EXPECT_TRUE(t.update(false, {303, 302}, 0.2, true).click);
}

}  // namespace
}  // namespace viz
