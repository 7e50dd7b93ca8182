#pragma once
// The window's layout as one object (issue #50): where the panels go this frame
// (view_layout.h computes it), which of App's own panels are shown, whether the panels show
// at all, the lecture mode's fonts and colours, the docked edges and the 3D view's rectangle
// between them, and the framebuffer's size. App owns it; the tools place their windows
// through it (host.layout().place(...)).
#include <algorithm>
#include <string>

#include <glm/glm.hpp>

#include "view_layout.h"

struct ImFont;

namespace viz {

/// Fonts main() loaded: the normal and the lecture (large) size, proportional and mono.
struct Fonts {
  ImFont* ui = nullptr;
  ImFont* ui_large = nullptr;
  ImFont* mono = nullptr;
  ImFont* mono_large = nullptr;
};

/// The panels App shows or hides itself (`panel NAME on|off`); the tools' own windows have
/// their own switch.
struct PanelSwitches {
  bool main = true, ray = true, steps = true, code = true, legend = true;
  /// The switch `panel NAME` sets (scene, ray, steps, code, legend), or nullptr when NAME
  /// is a tool's window.
  bool* find(const std::string& name);
};

/// Framebuffer pixels per window unit, from ImGui's display (1 where it does not say): window
/// coordinates (the mouse, the panels) times this are the framebuffer's (the 3D view).
glm::vec2 display_scale();

class WindowLayout {
 public:
  void set_fonts(const Fonts& fonts) { fonts_ = fonts; }
  /// The monospace font of the code and variables panels (large in lecture mode).
  ImFont* mono() const { return lecture_ ? fonts_.mono_large : fonts_.mono; }

  // ---- Switches
  bool ui_visible() const { return ui_visible_; }
  void set_ui_visible(bool on) { ui_visible_ = on; }
  bool lecture() const { return lecture_; }
  void set_lecture(bool on) { lecture_ = on; }
  bool* lecture_switch() { return &lecture_; }
  PanelSwitches& panels() { return panels_; }
  const PanelSwitches& panels() const { return panels_; }
  /// The Variables panel shares the left column with the controls (the traversal mode
  /// only): when it comes or goes the controls change height, so the layout is redone.
  void set_vars_column(bool on);
  bool vars_column() const { return vars_column_; }
  /// Back to the defaults (a playlist going back): every panel shown, laid out again.
  void reset();

  // ---- Per frame
  /// Starts a frame: the lecture mode's fonts and colours when it changed (the 3D view's
  /// background too), and no panel docked yet.
  void begin_frame();
  /// The panels' rectangles for this frame's display and font; re-applied to the windows
  /// for two frames after a change (the fonts take effect a frame late).
  void layout_windows();
  /// Lays the panels out again (a panel docked along an edge came or went, the window resized).
  void relayout() { frames_left_ = 2; }
  /// Where a panel at `rect` goes this frame; `docks` notes it among the docked edges.
  PanelPlace place(const WindowRect& rect, bool docks = true);
  /// After the panels: the 3D view's rectangle between the docked edges, and the
  /// framebuffer's size (window size times the display's scale).
  void end_frame();
  /// Before drawing into a framebuffer of `size`: the view's rectangle clamped to it.
  void clamp_to(glm::ivec2 size);
  /// Whether the layout is settled (no relayout pending): the camera frames then.
  bool settled() const { return frames_left_ == 0; }
  /// Frames to render until the panels are laid out: a script's `settle`.
  int frames_to_settle() const { return frames_left_ + 1; }

  // ---- Results
  const PanelLayout& rects() const { return rects_; }
  const DockEdges& dock() const { return dock_; }
  bool applying() const { return apply_; }
  /// The 3D view in framebuffer pixels (x, y from the top-left, width, height).
  glm::ivec4 view() const { return view_; }
  glm::ivec2 view_size() const { return {view_.z, view_.w}; }
  /// The 3D view's width over its height: the camera's aspect.
  float view_aspect() const { return static_cast<float>(view_.z) / static_cast<float>(std::max(view_.w, 1)); }
  glm::ivec2 framebuffer() const { return framebuffer_; }
  void set_framebuffer(glm::ivec2 size) { framebuffer_ = size; }
  glm::vec4 background() const { return background_; }

 private:
  void apply_lecture_mode();

  Fonts fonts_;
  PanelSwitches panels_;
  bool ui_visible_ = true;
  bool lecture_ = false;  // large fonts, high contrast
  bool lecture_applied_ = false;
  bool vars_column_ = true;
  PanelLayout rects_;
  bool apply_ = false;     // this frame: move the windows to rects_
  int frames_left_ = 2;    // frames left that (re)apply the layout
  glm::vec2 display_{0.0f};
  DockEdges dock_;         // this frame's docked panels
  /// The 3D view: the part of the framebuffer between the panels docked left and right
  /// (and above one docked along the bottom), so nothing hides the framed scene. The
  /// camera's aspect, picking and the heat map all use it.
  glm::ivec4 view_{0, 0, 1280, 720};
  glm::ivec2 framebuffer_{1280, 720};
  glm::vec4 background_{0.075f, 0.085f, 0.105f, 1.0f};
};

}  // namespace viz
