#pragma once
// Plain data the panels show, and small ImGui helpers shared by them (the tools in tools/
// have the panels themselves).
#include <string>
#include <vector>

#include "vec_math.h"
#include "view_layout.h"

struct ImFont;

namespace viz {

/// What the scene section shows about the loaded scene.
struct SceneInfo {
  std::string spec;        ///< as loaded: a path or "procedural:NAME"
  std::string name;        ///< Scene::name()
  size_t triangles = 0;
  size_t vertices = 0;
  size_t degenerate = 0;
  accel::Aabb bounds;
  double load_ms = 0.0;    ///< wall time of accel::load_scene
};

/// Frame timing, smoothed by App so the numbers are readable.
struct FrameTiming {
  double frame_ms = 0.0;
  double fps = 0.0;
};

/// Mutable UI state of the scene section, owned by StructureSession.
struct ScenePanelState {
  std::string obj_path;                   ///< the "Load mesh" path field
  std::string load_error;                 ///< last load error (shown in red), empty if none
};

namespace ui {

/// 1234567 -> "1,234,567": triangle counts of real scenes are long numbers.
std::string with_separators(size_t n);
/// One number through a printf `format` ("%.1f ms"): the panels' labels.
std::string fmt(const char* format, double v);
/// "(x, y, z)" with 4 significant digits.
std::string format_vec(const accel::Vec3& v);
/// Bytes as "12.3 MB".
std::string format_bytes(size_t bytes);
/// One label/value row of a two-column table.
void stat_row(const char* label, const std::string& value);
/// A row whose long value keeps its tail, with the whole text as tooltip.
void path_row(const char* label, const std::string& path);
/// A row whose long value keeps its head ("..." at the end), with the whole text as tooltip.
void text_row(const char* label, const std::string& value, size_t max_chars = 20);
/// A "(?)" marker whose tooltip is `text` (imgui_demo's HelpMarker).
void help_marker(const char* text);
/// Red error text wrapped at `width` pixels.
void error_text(const std::string& text, float width);
/// Places the next window at `place.rect` when the layout is (re)applied, and the first time
/// it appears; otherwise the user may move it. A zero size leaves the size alone.
void place(const PanelPlace& place);
/// Inside a window's Begin/End: notes the window in place.dock (when given), so a window
/// along the left or right edge narrows the 3D view.
void note_docked(const PanelPlace& place);
/// A tool's panel: placed (place()), its background slightly translucent, begun, and noted
/// docked. False when it is collapsed (its End() already called): draw nothing. True: draw
/// the contents, then ImGui::End().
bool begin_panel(const PanelPlace& place, const char* title);
/// The body of a pseudo-code panel: a scrolling child `id` listing `lines` in `mono` (may be
/// null), line `current` (-1: none) highlighted and kept in view; `scrolled` remembers the
/// line last scrolled to (the panel's state), so the user may scroll away until it changes.
void code_listing(const char* id, const std::vector<std::string>& lines, int current, ImFont* mono,
                  int& scrolled);

}  // namespace ui
}  // namespace viz
