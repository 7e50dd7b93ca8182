#pragma once
// What a tool (tools/tool.h) may ask of the App that holds the tools: the other tools, by
// type (host.tool<TrapTool>()); App's own state (script mode, the window's layout, the
// camera); and the session's events told to every tool. App implements the few virtual
// members; the rest are the wiring between tools that many of them use (a new ray restarts
// an open comparison), written once here (tool_host.cpp) so that App names no tool.
#include <cstddef>
#include <span>
#include <string>
#include <typeinfo>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "geometry.h"
#include "playback_clock.h"
#include "result.h"
#include "tools/tool.h"

namespace viz {

class BuildPlayer;
class CameraControl;
class RayDebugger;
class ScriptHost;
class StructureSession;
class WindowLayout;
struct HeatmapView;
struct Preset;
struct ScriptCommand;

class ToolHost {
 public:
  virtual ~ToolHost() = default;

  // ---- The tools, in App's order
  virtual std::span<Tool* const> tools() const = 0;
  /// The tool of type T (every tool is in the list once: a missing one is a programming error).
  template <class T>
  T& tool() const {
    for (Tool* t : tools())
      if (T* found = dynamic_cast<T*>(t)) return *found;
    missing_tool(typeid(T));
  }
  /// The three tools most others read: the scene and structure, the debug ray, the construction.
  StructureSession& session() const;
  RayDebugger& ray() const;
  BuildPlayer& build() const;

  // ---- App's state
  /// Script mode: builds and other work run to the end before a command returns.
  virtual bool synchronous() const = 0;
  /// The window's layout: panels, lecture mode, the 3D view's rectangle.
  virtual WindowLayout& layout() const = 0;
  /// The camera of the 3D view.
  virtual CameraControl& camera() const = 0;
  /// Tells every tool `event`, in App's order.
  virtual void notify(ToolEvent event) = 0;
  /// Runs one parsed script command (a playlist's state runs its commands through this).
  virtual accel::Status execute(const ScriptCommand& command, ScriptHost& host) = 0;
  /// The window's size in window coordinates (a playlist's `size` in the window).
  virtual void resize_window(int width, int height) = 0;
  /// Sets the window's title again (the playlist's state, a recording).
  virtual void refresh_title() = 0;

  // ---- Shared wiring (tool_host.cpp)
  /// After a command that loads a scene or starts a build: in script mode the structure
  /// must be there; in the window it builds in the background.
  accel::Status loaded() const;
  /// Tells the tools what the session did (a scene loaded, a structure installed).
  void sync_session();
  /// Lays the panels out again; shows them.
  void relayout();
  void show_ui();
  /// Renders the frames that lay the panels out and frame a new scene: afterwards the
  /// camera is the one drawn, so a ray or image from it matches the screen.
  void settle_camera(ScriptHost& host);
  /// The 3D view in framebuffer pixels (x, y from the top-left, width, height), and the
  /// framebuffer's size.
  glm::ivec4 view_area() const;
  glm::ivec2 framebuffer() const;
  /// While recording: a command moved `clock` from step `from` to where it is now; walks
  /// there again one step and one frame at a time, so the recording holds every step.
  void walk_recorded(accel::PlaybackClock& clock, size_t from, ScriptHost& host);
  /// Makes `ray` the debug ray (an open comparison follows it).
  void set_ray(const accel::Ray& ray, const std::string& origin);
  /// Shoots the debug ray through framebuffer pixel (px, py), as a click does.
  void shoot_at_pixel(float px, float py, bool from_saved_view);
  /// Runs the comparison on the debug ray.
  void start_compare();
  /// Starts the sweep configured in the sweep tool.
  accel::Status start_sweep();
  /// Records the current structure's build (the construction mode).
  void construct();
  /// What the heat map images: the camera, the structure and the view's size.
  HeatmapView heatmap_view() const;
  /// Loads a preset: its scene, camera and ray.
  accel::Status apply_preset(const Preset& preset);
  /// Loads a lecture trap: its scene and structure, and shoots its ray.
  accel::Status load_trap(const std::string& name);
  /// Loads a playlist and queues its first state.
  accel::Status load_playlist(const std::string& path);
  /// Goes to the playlist's state `index` (the viewer reset first when going back).
  void go_to_state(size_t index);
  /// Runs the playlist's queued commands (`host` null: one per frame, in the window).
  void run_playlist(ScriptHost* host);

 private:
  [[noreturn]] static void missing_tool(const std::type_info& type);
};

}  // namespace viz
