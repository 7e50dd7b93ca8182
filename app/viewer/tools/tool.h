#pragma once
// One viewer tool, one interface (issue #50, after Scotty3D's modes and imgui's demo
// windows): its keys, its script verbs, its GL objects, what it does each frame, its
// windows and its part of the main panel, what it draws into the 3D view, its defaults and
// its lines of the saved state. App (app.h) holds the tools in one list
// (tools/tool_list.cpp) and calls each in the list's order; it names none of them. What a
// tool needs of another it asks the ToolHost for (tool_host.h: host.tool<T>()).
//
// Every member has a default that does nothing, so a tool overrides only what it has.
#include <string>
#include <vector>

#include "commands.h"

namespace viz {

class Renderer;
class ToolHost;
struct MouseFrame;

/// What happened to the session or the debug ray: App tells every tool (on_event).
enum class ToolEvent {
  SceneLoaded,        ///< a new scene: rays, comparisons and images of the old one mean nothing
  SceneEdited,        ///< the blackboard's scene changed in place (the ray stays)
  StructureInstalled, ///< a new structure is shown
  RayChanged,         ///< a new debug ray (an open comparison follows it)
  PlaylistReset,      ///< a playlist goes back: return to the viewer's defaults
  ColorsChanged,      ///< the colour scheme changed (color_scheme.h)
};

/// The main panel's sections that several tools share, in their order; a tool with a
/// section of its own writes it under Own (its collapsing header is its own).
enum class PanelSection { Scene, Structure, Display, Own };

/// Where in the 3D view's drawing a tool draws: under the mesh (the blackboard's grid), the
/// structure and its highlights, or on top of everything (depth test off, the corners).
enum class DrawLayer { Under, Scene, Over };

class Tool {
 public:
  virtual ~Tool() = default;

  /// Its name in the help's key groups ("heat map").
  virtual const char* name() const = 0;

  // ---- Keys and verbs (commands.h): rows made once, when App is constructed
  /// The keys it answers, in the order a press is offered to them.
  virtual std::vector<KeyBinding> keys(ToolHost&) { return {}; }
  /// Its script verbs, each one registration (commands.h: name, usage, help, typed
  /// arguments, parse, run), bound to the tool and `host` into `table`.
  virtual void add_verbs(VerbTable& /*table*/, ToolHost& /*host*/) {}

  // ---- GL: created once the window's context is current, released before it goes
  virtual void init_gl() {}
  virtual void release_gl() {}
  /// Waits for its background jobs (they may read the scene and structure, or GL's data).
  virtual void wait() {}

  // ---- Per frame, in this order
  /// What the session did, or a new ray (ToolEvent); may come several times a frame.
  virtual void on_event(ToolEvent, ToolHost&) {}
  /// The mouse over the 3D view this frame (camera_control.h): its clicks and drags.
  virtual void mouse(const MouseFrame&, ToolHost&) {}
  /// Before the panels: finished background jobs, the animation's clock (`dt` seconds;
  /// 0 in script mode, where nothing advances on its own), what the frame shows.
  virtual void update(ToolHost&, float /*dt*/) {}
  /// Its part of the main panel (`section`: the shared sections, then Own).
  virtual void section(ToolHost&, PanelSection) {}
  /// Its windows (placed by host.layout()), when the panels are shown.
  virtual void panels(ToolHost&) {}
  /// `panel NAME on|off` for a window it owns: true when NAME is one of its.
  virtual bool set_panel(const std::string& /*name*/, bool /*on*/) { return false; }
  /// Drawn with or without the panels (a playlist's title, the status notices).
  virtual void overlay(ToolHost&) {}
  /// After the panels (which may have moved things): the highlights the frame draws.
  virtual void late_update(ToolHost&) {}
  /// Uploads its GL data before the frame is drawn.
  virtual void sync_gl(Renderer&, ToolHost&) {}
  /// Draws into the 3D view.
  virtual void draw(Renderer&, ToolHost&, DrawLayer) {}

  /// Appends what it adds to the window's title (" - recording (R stops)").
  virtual void window_title(std::string& /*title*/, const ToolHost&) const {}

  // ---- The saved state (`save-state`, --restore)
  /// Appends its lines (script commands) to the state script.
  virtual void save_state(std::string& /*script*/, const ToolHost&) const {}
};

}  // namespace viz
