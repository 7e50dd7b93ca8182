#pragma once
// The viewer's command scripts (`accelviz --script FILE`): one command per line, `#`
// starts a comment. Parsed here into plain commands, GL-free, so the parser is unit-tested;
// App executes them and main() renders for the screenshot commands. The verbs are rows that
// their tools declare (commands.h): script_verbs.h lists each module's, with its usage and
// help; `accelviz --list commands` prints them and docs/viewer.md's table is that print.
// Errors are "SCRIPT:LINE: message".
#include <array>
#include <string>
#include <vector>

#include "result.h"

namespace viz {

enum class CommandKind {
  Size, Scene, Preset, Structure, Kernel, Camera, RayAtPixel, Ray, Step, Show, Heatmap, Mesh,
  EmptyCells, Nodes, Opacity, Panel, Large, Compare, Sweep, Screenshot, Frames, PrintHit, PrintStep,
  PrintRay, PrintStats, PrintFrameTime, LoadBench, ShowChart, Construct, ConstructUntil, BuildStep, PrintBuildStep,
  SahPlot,
  PrintVars, PrintClaims, Trap, PrintNaive, PrintTrap,
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
  std::vector<std::string> params;   ///< structure: key=value list; show-chart: its settings;
                                     ///< construct-until: accelviz-cli check's comment lines atop the script
  std::array<float, 8> values{};     ///< camera (6 or 7), ray (6, or 8 with tmin tmax), ray-at-pixel (2), sweep (lo, hi),
                                     ///< add2d (6: from values[0]), ray2d (4)
  bool has_fov = false;              ///< camera: FOVY given
  size_t bytes = 0;                  ///< memory-limit (0: the default)
  size_t calls = 0;                  ///< construct-until N; structure: the N of a construct-until after it
                                     ///< (a failed build's replay: its build stops there too), else 0
  int ints[2] = {0, 0};              ///< size W H; step / build-step count; sweep steps; frame count;
                                     ///< record: fps, and size W H in values[0..1] (0: as captured)
  StepMode step = StepMode::Forward;  ///< step, build-step (no Hit)
  ShowMode show = ShowMode::All;
  bool on = true;                    ///< panel/large/empty-cells/nodes/show-chart/sah-plot on|off; mode: 2d
};

/// Parses `text` (the script named `script_name` in messages). Validates everything that
/// needs no scene or window: command names, argument counts and numbers, structure names
/// and parameters (against the registry, as accelviz-cli does). Error: "SCRIPT:LINE: message".
/// A `structure` line followed by `construct-until N` gets N too (ScriptCommand::calls): a
/// failed build's replay builds only as far as the check's build got.
accel::Result<std::vector<ScriptCommand>> parse_script(const std::string& text, const std::string& script_name);

/// Reads and parses a script file. Error names the file when it cannot be read.
accel::Result<std::vector<ScriptCommand>> load_script(const std::string& path);

/// "SCRIPT:LINE: message", the format of every script error.
std::string script_error(const std::string& script_name, int line, const std::string& message);

}  // namespace viz
