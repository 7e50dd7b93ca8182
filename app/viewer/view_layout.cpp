#include "view_layout.h"

#include <algorithm>
#include <cmath>

namespace viz {

PanelLayout compute_layout(glm::vec2 display, float em, bool lecture, bool main_open) {
  PanelLayout l;
  const float pad = 0.4f * em;
  const float w = display.x, h = display.y;
  // Left: controls (collapsed in lecture mode, for a bigger view). Right: the debug ray, the
  // pseudo code and the step list, wide enough for the lecture's code lines.
  const float left = std::min(21.0f * em, 0.3f * w);
  const float right = std::min(34.0f * em, (lecture ? 0.42f : 0.4f) * w);
  // The traversal's variables under the controls (in lecture mode the controls collapse to
  // their title bar and the variables take the column).
  const float main_h = lecture ? 2.0f * em : std::round(0.56f * h);
  l.main = {{pad, pad}, {left, h - 2.0f * pad}};
  const float vars_y = 2.0f * pad + main_h;
  l.vars = {{pad, vars_y}, {left, std::max(h - vars_y - pad, 6.0f * em)}};
  if (!lecture) l.main.size.y = main_h;
  const float rx = w - right - pad;
  const float ray_h = lecture ? 0.4f * h : std::max(0.42f * h, 19.5f * em);
  const float code_h = lecture ? 0.38f * h : 0.32f * h;
  l.ray = {{rx, pad}, {right, ray_h}};
  l.code = {{rx, 2.0f * pad + ray_h}, {right, code_h}};
  l.steps = {{rx, 3.0f * pad + ray_h + code_h}, {right, std::max(h - ray_h - code_h - 4.0f * pad, 4.0f * em)}};
  // Compare table and sweep plot: temporary and wide (they need the width), right of the left
  // column to the right edge -- over the 3D view's lower part and the steps list, never over
  // the Variables panel, which a student reads beside the comparison.
  const float cx = left + 2.0f * pad;
  const float bottom_h = std::min(0.34f * h, 16.0f * em);
  l.bottom = {{cx, h - bottom_h - pad}, {std::max(w - cx - pad, 10.0f * em), bottom_h}};
  l.legend = {{cx, pad}, {0.0f, 0.0f}};
  // The bench chart needs room more than the debug ray does: everything right of the
  // controls (the whole width when they are hidden or collapsed).
  const float chart_x = main_open && !lecture ? cx : pad;
  l.chart = {{chart_x, pad}, {w - chart_x - pad, h - 2.0f * pad}};
  l.status = {{cx, pad}, {0.0f, 0.0f}};
  // The tree diagram: under the 3D view, between the columns (the left one holds the
  // controls and the Variables panel, also in lecture mode), tall enough for a few levels
  // and the node numbers.
  const float tree_x = cx;
  const float tree_h = lecture ? 0.42f * h : std::min(0.4f * h, 22.0f * em);
  l.tree = {{tree_x, h - tree_h - pad}, {std::max(rx - pad - tree_x, 10.0f * em), tree_h}};
  return l;
}

void note_docked(DockEdges& edges, float display_width, glm::vec2 pos, glm::vec2 size) {
  const float w = display_width;
  if (pos.x < 0.3f * w && pos.x + size.x < 0.5f * w) edges.left = std::max(edges.left, pos.x + size.x);
  if (pos.x + size.x > 0.7f * w && pos.x > 0.5f * w) edges.right = std::min(edges.right, pos.x);
}

void note_docked_bottom(DockEdges& edges, float display_height, glm::vec2 pos, glm::vec2 size) {
  const float h = display_height;
  if (pos.y > 0.3f * h && pos.y + size.y > 0.9f * h)
    edges.bottom = edges.bottom > 0.0f ? std::min(edges.bottom, pos.y) : pos.y;
}

glm::ivec4 view_rect(const DockEdges& edges, glm::vec2 display, glm::vec2 scale, bool ui_visible) {
  const float w = display.x;
  float left = ui_visible ? edges.left : 0.0f, right = ui_visible ? edges.right : w;
  if (right - left < std::max(kMinViewFraction * w, kMinViewPixels)) {
    left = 0.0f;
    right = w;
  }
  const float sx = scale.x > 0.0f ? scale.x : 1.0f, sy = scale.y > 0.0f ? scale.y : 1.0f;
  const int fb_h = static_cast<int>(std::lround(display.y * sy));
  const int x0 = static_cast<int>(std::lround(left * sx)), x1 = static_cast<int>(std::lround(right * sx));
  // A bottom panel shortens the view from below (the view keeps its top at y = 0).
  int view_h = fb_h;
  if (ui_visible && edges.bottom > 0.0f && edges.bottom >= kMinViewHeightFraction * display.y)
    view_h = static_cast<int>(std::lround(std::min(edges.bottom, display.y) * sy));
  return {x0, 0, std::max(x1 - x0, 1), std::max(view_h, 1)};
}

}  // namespace viz
