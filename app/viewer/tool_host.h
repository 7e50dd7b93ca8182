#pragma once
// What a tool's key actions and script verbs (commands.h) may ask of the App that holds the
// tools: the few tools others move (the session's structure, the debug ray, the
// construction), App's own state (script mode, layout, camera), and App's wiring between
// tools (a new ray restarts an open comparison). App implements it; each tool's
// key_bindings() and add_verbs() take it (its verbs' runs get it), as Scotty3D's modes take
// their manager.
#include <cstddef>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "geometry.h"
#include "playback_clock.h"
#include "result.h"

namespace viz {

class BuildPlayer;
class RayDebugger;
class ScriptHost;
class StructureSession;
struct HeatmapView;
struct Preset;

class ToolHost {
 public:
  virtual ~ToolHost() = default;

  // ---- The tools another tool's rows may read or move
  virtual StructureSession& session() = 0;
  virtual RayDebugger& ray() = 0;
  virtual BuildPlayer& build() = 0;

  // ---- App's state
  /// Script mode: builds and other work run to the end before a command returns.
  virtual bool synchronous() const = 0;
  /// After a command that loads a scene or starts a build: in script mode the structure
  /// must be there; in the window it builds in the background.
  virtual accel::Status loaded() const = 0;
  /// Tells the tools what the session did (a scene loaded, a structure installed).
  virtual void sync_session() = 0;
  /// Lays the panels out again (a panel docked along an edge came or went).
  virtual void relayout() = 0;
  /// Shows the panels (a command that opens a window wants it seen).
  virtual void show_ui() = 0;
  /// Renders the frames that lay the panels out and frame a new scene: afterwards the
  /// camera is the one drawn, so a ray or image from it matches the screen.
  virtual void settle_camera(ScriptHost& host) = 0;
  /// The 3D view in framebuffer pixels (x, y from the top-left, width, height), and the
  /// framebuffer's size.
  virtual glm::ivec4 view_area() const = 0;
  virtual glm::ivec2 framebuffer() const = 0;
  /// While recording: a command moved `clock` from step `from` to where it is now; walks
  /// there again one step and one frame at a time, so the recording holds every step.
  /// Nothing otherwise.
  virtual void walk_recorded(accel::PlaybackClock& clock, size_t from, ScriptHost& host) = 0;

  // ---- App's wiring between tools
  /// Makes `ray` the debug ray (an open comparison follows it).
  virtual void set_ray(const accel::Ray& ray, const std::string& origin) = 0;
  /// Shoots the debug ray through framebuffer pixel (px, py), as a click does.
  virtual void shoot_at_pixel(float px, float py, bool from_saved_view) = 0;
  /// Runs the comparison on the debug ray.
  virtual void start_compare() = 0;
  /// Starts the sweep configured in the sweep tool.
  virtual accel::Status start_sweep() = 0;
  /// Records the current structure's build (the construction mode).
  virtual void construct() = 0;
  /// What the heat map images: the camera, the structure and the view's size.
  virtual HeatmapView heatmap_view() const = 0;
  /// Loads a preset: its scene, camera and ray.
  virtual accel::Status apply_preset(const Preset& preset) = 0;
  /// Loads a lecture trap: its scene and structure, and shoots its ray.
  virtual accel::Status load_trap(const std::string& name) = 0;
  /// Loads a playlist and queues its first state.
  virtual accel::Status load_playlist(const std::string& path) = 0;
  /// Goes to the playlist's state `index` (the viewer reset first when going back).
  virtual void go_to_state(size_t index) = 0;
  /// Runs the playlist's queued commands (`host` null: one per frame, in the window).
  virtual void run_playlist(ScriptHost* host) = 0;
};

}  // namespace viz
