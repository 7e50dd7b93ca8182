#pragma once
// GL-free window layout: where the panels go, which of them dock along the left and right
// edges, and the 3D view's rectangle between them (the camera frames the scene into it).
// Owns nothing; WindowLayout (window_layout.h) keeps the results between frames.
#include <glm/glm.hpp>

namespace viz {

/// A window's place in window coordinates (ImGui's, from the top-left).
struct WindowRect {
  glm::vec2 pos{0.0f}, size{0.0f};
};

/// Where every panel goes at a given display size and font size.
struct PanelLayout {
  WindowRect main, vars, ray, code, steps, bottom, legend, status, chart;
  /// The tree diagram: docked along the bottom between the left and right columns.
  WindowRect tree;
};

/// The panels' rectangles for a display of `display` (window coordinates), font size `em`,
/// in lecture mode or not, with the main panel open or not (the chart takes its room).
PanelLayout compute_layout(glm::vec2 display, float em, bool lecture, bool main_open);

/// The inner edges of the panels docked left and right in this frame (window coordinates).
struct DockEdges {
  float left = 0.0f;   ///< right edge of the left column (0: none)
  float right = 0.0f;  ///< left edge of the right column (display width: none)
  float bottom = 0.0f; ///< top edge of the panel docked along the bottom (0: none)
};

/// Notes a window at `pos` with `size`: along the left or right edge of a display
/// `display_width` wide it narrows the 3D view; one in the middle floats over it.
void note_docked(DockEdges& edges, float display_width, glm::vec2 pos, glm::vec2 size);

/// Notes a window docked along the bottom of a display `display_height` tall (its lower
/// edge near the display's, its top in the lower part): the 3D view ends above it.
void note_docked_bottom(DockEdges& edges, float display_height, glm::vec2 pos, glm::vec2 size);

/// The narrowest 3D view between docked panels, as a fraction of the width and in window
/// pixels: narrower, and panels over the scene are better (small windows, e.g. tests).
inline constexpr float kMinViewFraction = 0.25f;
inline constexpr float kMinViewPixels = 320.0f;

/// The lowest 3D view above a bottom panel, as a fraction of the height: lower, and the
/// bottom panel floats over the scene instead.
inline constexpr float kMinViewHeightFraction = 0.35f;

/// The 3D view: (x, y from the top-left, width, height) in framebuffer pixels, between the
/// docked edges (and above a bottom one) when the UI is visible. `scale` is the framebuffer pixels per window unit.
glm::ivec4 view_rect(const DockEdges& edges, glm::vec2 display, glm::vec2 scale, bool ui_visible);

/// Where a tool's panel goes this frame, and the docked edges it may narrow.
struct PanelPlace {
  WindowRect rect;           ///< position and size (size 0: automatic)
  bool apply = false;        ///< force them (the layout is being (re)applied)
  DockEdges* dock = nullptr; ///< noted when the panel is shown (nullptr: floats)
};

}  // namespace viz
