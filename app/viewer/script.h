#pragma once
// The viewer's command scripts (`accelviz --script FILE`): one command per line, `#`
// starts a comment. Parsed here into plain commands, GL-free, so the parser is unit-tested;
// App executes them and main() renders for the screenshot commands.
//
//   size W H                          window size in pixels
//   scene PATH | scene procedural:NAME
//   preset NAME                       a preset: scene, camera, ray (see presets.h)
//   structure NAME [key=value ...]    as accelviz-cli --structure NAME --param key=value
//   kernel watertight|moller|double
//   memory-limit SIZE | memory-limit default
//                                     the builds' memory budget, as accelviz-cli --memory-limit
//                                     (512M, 4G, 25%); a build over it is a script error
//   camera EX EY EZ TX TY TZ [FOVY_DEG]
//   ray-at-pixel X Y                  shoot like a click; pixel from the top-left
//   ray OX OY OZ DX DY DZ [TMIN TMAX]  (TMAX may be inf)
//   mode 2d|3d                        the blackboard (a 2D scene in the plane z = 0, seen
//                                     from above; an empty one unless a 2D scene is loaded)
//                                     or back to the last 3D scene
//   scene2d FILE                      load a 2D scene file (docs/hits.md) into the blackboard
//   add2d tri X1 Y1 X2 Y2 X3 Y3       add a triangle to the blackboard (2D mode)
//   ray2d OX OY DX DY                 the debug ray in the plane (2D mode)
//   save2d FILE                       write the blackboard's scene as a 2D scene file
//   step N | step end | step back N | step hit | step start
//   show depth=A..B | show depth=A | show leaves | show all
//   heatmap off|nodes|prims
//   heatmap-scale auto | heatmap-scale LO HI
//                                     the heat map's colour scale: 0..p99 of each image, or
//                                     fixed (kept across structures, so their images compare)
//   heatmap-diff NAME [key=value ...] | heatmap-diff off
//                                     the difference view: the current structure's cost
//                                     minus NAME's per pixel, diverging colours
//   print-heatmap                     "heat map: METRIC WxH, scale LO..HI (auto|fixed), mean M, max X"
//   mesh solid|translucent|wireframe|off
//   empty-cells on|off                grid: draw empty cells too
//   nodes on|off                      draw the structure's nodes (the ray's highlights stay)
//   opacity A                         opacity of the structure's lines, 0.05..1
//   panel on|off                      all panels; or `panel NAME on|off` for one of
//                                     scene, ray, steps, code, compare, sweep, legend,
//                                     vars, strip (the t-axis strip), trap
//   large on|off                      large-font / high-contrast lecture mode
//   compare                           fill the "same ray, every structure" table
//   sweep PARAM LO HI STEPS           parameter sweep of the current structure (synchronous)
//   screenshot PATH                   write a PNG
//   frames PREFIX                     PREFIX0000.png ... one PNG per remaining step
//   construct                         record the current structure's build (construction mode)
//   build-step N | build-step end | build-step back N | build-step start
//   print-build-step                  "build step K/N: TEXT" (K steps applied)
//   sah-plot on|off                   the construction panel's SAH cost plot
//   tree on|off                       the "Tree" window: the hierarchy diagram (grid: cell walk)
//   tree-select NODE [isolate]        select node NODE in the tree (3D highlight, numbers);
//                                     isolate: draw only its subtree in 3D
//   playlist FILE                     load a lecture playlist (playlist.h), show its first state
//   next | prev                       the playlist's next / previous state
//   print-state                       "state K/N: TITLE"
//   record PATH.gif|PATH.mp4 [fps=N] [ui=on|off] [size=WxH]
//                                     record one frame per step moved (step, build-step)
//                                     until `record stop`; fps 1..60 (default 4), ui=off:
//                                     the 3D view only
//   record stop                       finish the file
//   colors viridis|cividis|turbo [hits=blue-orange|green-red]
//                                     the colour map of depths, counts and the heat map, and
//                                     the hit / miss pair (defaults: viridis, blue-orange)
//   save-state FILE                   write the state (scene, structure, camera, ray, step) as
//                                     the script that restores it (accelviz --restore FILE)
//   print-hit                         "hit PRIM T" or "miss"
//   print-step                        the current step as one line
//   print-vars                        "vars: name=value ..." of the current step (the
//                                     traversal's recorded variables, closest_hit, the
//                                     stack or queue as NODE:KEY,...)
//   trap pq|kd|grid                   load a lecture trap's scene and structure, shoot its ray
//   print-naive                       "naive hit PRIM T" or "naive miss": what a traversal
//                                     stopping at the first leaf with a hit would answer
//   print-ray                         "ox oy oz dx dy dz" as C99 hex floats (a rays-file line)
//   print-stats                       build statistics of the current structure, one line
//   print-frame-time N                render N frames, print the mean frame time
//   trace-rays SPEC                   trace a batch of rays through the current structure on
//                                     one thread (SPEC as accelviz-cli --rays: random:N:SEED,
//                                     primary:W:H or a rays file) and print
//                                     "trace-rays SPEC: N rays, H hits, T ms (1 thread)"
//   load-bench FILE                   load a bench JSON (accelviz-cli bench --out-json) and
//                                     open the "Speed vs error" chart
//   show-chart on|off [SETTING ...]   show or hide the chart; settings x=errors|t-error,
//                                     speed=mt|1t, y=linear|log, labels=on|off, group=N
// Errors are "SCRIPT:LINE: message".
#include <array>
#include <string>
#include <vector>

#include "result.h"

namespace viz {

enum class CommandKind {
  Size, Scene, Preset, Structure, Kernel, Camera, RayAtPixel, Ray, Step, Show, Heatmap, Mesh,
  EmptyCells, Nodes, Opacity, Panel, Large, Compare, Sweep, Screenshot, Frames, PrintHit, PrintStep,
  PrintRay, PrintStats, PrintFrameTime, LoadBench, ShowChart, Construct, BuildStep, PrintBuildStep, SahPlot,
  PrintVars, Trap, PrintNaive,
  Tree, TreeSelect,
  Playlist, Next, Prev, PrintState, Record, RecordStop, Colors, HeatmapScale, PrintHeatmap, HeatmapDiff,
  MemoryLimit, TraceRays, Mode, Scene2d, Add2d, Ray2d, Save2d, SaveState,
};

enum class StepMode { Forward, Back, End, Hit, Start };
enum class ShowMode { All, Leaves, Depth };

/// One parsed command; only the fields of its kind are meaningful.
struct ScriptCommand {
  CommandKind kind = CommandKind::Size;
  int line = 0;                      ///< 1-based line in the script
  std::string name;                  ///< scene spec, structure, kernel, preset, panel, path, prefix, param, trap
  std::vector<std::string> params;   ///< structure: key=value list; show-chart: its settings
  std::array<float, 8> values{};     ///< camera (6 or 7), ray (6, or 8 with tmin tmax), ray-at-pixel (2), sweep (lo, hi),
                                     ///< add2d (6: from values[0]), ray2d (4)
  bool has_fov = false;              ///< camera: FOVY given
  size_t bytes = 0;                  ///< memory-limit (0: the default)
  int ints[2] = {0, 0};              ///< size W H; step / build-step count; sweep steps; frame count;
                                     ///< record: fps, and size W H in values[0..1] (0: as captured)
  StepMode step = StepMode::Forward;  ///< step, build-step (no Hit)
  ShowMode show = ShowMode::All;
  bool on = true;                    ///< panel/large/empty-cells/nodes/show-chart/sah-plot on|off; mode: 2d
};

/// Parses `text` (the script named `script_name` in messages). Validates everything that
/// needs no scene or window: command names, argument counts and numbers, structure names
/// and parameters (against the registry, as accelviz-cli does). Error: "SCRIPT:LINE: message".
accel::Result<std::vector<ScriptCommand>> parse_script(const std::string& text, const std::string& script_name);

/// Reads and parses a script file. Error names the file when it cannot be read.
accel::Result<std::vector<ScriptCommand>> load_script(const std::string& path);

/// "SCRIPT:LINE: message", the format of every script error.
std::string script_error(const std::string& script_name, int line, const std::string& message);

}  // namespace viz
