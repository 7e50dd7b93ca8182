#include "script.h"

#include <charconv>
#include <cstdio>
#include <cmath>
#include <limits>
#include <fstream>
#include <sstream>

#include "bench_chart.h"
#include "color_scheme.h"
#include "geometry.h"
#include "memory_budget.h"
#include "params.h"
#include "rays_io.h"
#include "registry.h"
#include "traps.h"
#include "video_writer.h"

namespace viz {
namespace {

std::vector<std::string> tokens_of(const std::string& line) {
  std::vector<std::string> tokens;
  std::istringstream in(line);
  std::string t;
  while (in >> t) {
    if (t[0] == '#') break;  // a comment runs to the end of the line
    tokens.push_back(t);
  }
  return tokens;
}

bool parse_int(const std::string& s, int* out) {
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, *out);
  return !s.empty() && ec == std::errc() && ptr == end;
}

bool parse_finite(const std::string& s, float* out) {
  return accel::parse_ray_number(s, out) && std::isfinite(*out);
}

bool parse_on_off(const std::string& s, bool* out) {
  if (s == "on") *out = true;
  else if (s == "off") *out = false;
  else return false;
  return true;
}

/// Parses the arguments of one command; returns an error message or "" on success.
std::string parse_command(const std::string& verb, const std::vector<std::string>& args, ScriptCommand& c) {
  const size_t n = args.size();
  auto count_error = [&](const char* usage) { return std::string("usage: ") + usage; };
  auto floats = [&](size_t first, size_t count, const char* usage) -> std::string {
    for (size_t i = 0; i < count; ++i) {
      if (!parse_finite(args[first + i], &c.values[i]))
        return "'" + args[first + i] + "' is not a finite number (" + usage + ")";
    }
    return "";
  };

  if (verb == "size") {
    c.kind = CommandKind::Size;
    if (n != 2) return count_error("size W H");
    if (!parse_int(args[0], &c.ints[0]) || !parse_int(args[1], &c.ints[1]) || c.ints[0] < 64 || c.ints[1] < 64 ||
        c.ints[0] > 8192 || c.ints[1] > 8192)
      return "size: W and H must be integers in 64..8192, got '" + args[0] + " " + args[1] + "'";
    return "";
  }
  if (verb == "scene") {
    c.kind = CommandKind::Scene;
    if (n != 1) return count_error("scene PATH | scene procedural:NAME");
    c.name = args[0];
    return "";
  }
  if (verb == "preset") {
    c.kind = CommandKind::Preset;
    if (n != 1) return count_error("preset NAME");
    c.name = args[0];
    return "";
  }
  if (verb == "structure") {
    c.kind = CommandKind::Structure;
    if (n < 1) return count_error("structure NAME [key=value ...]");
    c.name = args[0];
    c.params.assign(args.begin() + 1, args.end());
    auto choice = accel::parse_structure(c.name, c.params);
    return choice ? "" : choice.error().message;
  }
  if (verb == "kernel") {
    c.kind = CommandKind::Kernel;
    accel::Kernel k;
    if (n != 1 || !accel::parse_kernel(args[0], &k)) return count_error("kernel watertight|moller|double");
    c.name = args[0];
    return "";
  }
  if (verb == "camera") {
    c.kind = CommandKind::Camera;
    if (n != 6 && n != 7) return count_error("camera EX EY EZ TX TY TZ [FOVY_DEG]");
    if (auto e = floats(0, n, "camera EX EY EZ TX TY TZ [FOVY_DEG]"); !e.empty()) return e;
    c.has_fov = n == 7;
    if (c.has_fov && !(c.values[6] > 1.0f && c.values[6] < 170.0f))
      return "camera: FOVY_DEG must be in (1, 170) degrees, got " + args[6];
    if (c.values[0] == c.values[3] && c.values[1] == c.values[4] && c.values[2] == c.values[5])
      return "camera: eye and target are the same point";
    return "";
  }
  if (verb == "ray-at-pixel") {
    c.kind = CommandKind::RayAtPixel;
    if (n != 2) return count_error("ray-at-pixel X Y");
    return floats(0, 2, "ray-at-pixel X Y");
  }
  if (verb == "ray") {
    c.kind = CommandKind::Ray;
    const char* usage = "ray OX OY OZ DX DY DZ [TMIN TMAX]";
    if (n != 6 && n != 8) return count_error(usage);
    if (auto e = floats(0, 6, usage); !e.empty()) return e;
    if (c.values[3] == 0.0f && c.values[4] == 0.0f && c.values[5] == 0.0f) return "ray: the direction is zero";
    c.values[6] = 0.0f;
    c.values[7] = std::numeric_limits<float>::infinity();
    if (n == 8) {  // as in a rays file: TMAX may be inf; TMIN <= TMAX
      if (!parse_finite(args[6], &c.values[6])) return "'" + args[6] + "' is not a finite number (" + usage + ")";
      if (!accel::parse_ray_number(args[7], &c.values[7]) || std::isnan(c.values[7]) || c.values[7] == -INFINITY)
        return "'" + args[7] + "' is not a number or inf (" + usage + ")";
      if (!(c.values[6] <= c.values[7])) return "ray: TMIN is greater than TMAX";
    }
    return "";
  }
  if (verb == "mode") {
    c.kind = CommandKind::Mode;
    if (n != 1 || (args[0] != "2d" && args[0] != "3d")) return count_error("mode 2d|3d");
    c.on = args[0] == "2d";
    return "";
  }
  if (verb == "scene2d") {
    c.kind = CommandKind::Scene2d;
    if (n != 1) return count_error("scene2d FILE");
    c.name = args[0];
    return "";
  }
  if (verb == "add2d") {
    c.kind = CommandKind::Add2d;
    const char* usage = "add2d tri X1 Y1 X2 Y2 X3 Y3";
    if (n != 7 || args[0] != "tri") return count_error(usage);
    return floats(1, 6, usage);
  }
  if (verb == "save2d" || verb == "save-state") {
    c.kind = verb == "save2d" ? CommandKind::Save2d : CommandKind::SaveState;
    if (n != 1) return count_error(verb == "save2d" ? "save2d FILE" : "save-state FILE");
    c.name = args[0];
    return "";
  }
  if (verb == "ray2d") {
    c.kind = CommandKind::Ray2d;
    if (n != 4) return count_error("ray2d OX OY DX DY");
    if (auto e = floats(0, 4, "ray2d OX OY DX DY"); !e.empty()) return e;
    if (c.values[2] == 0.0f && c.values[3] == 0.0f) return "ray2d: the direction is zero";
    return "";
  }
  if (verb == "step") {
    c.kind = CommandKind::Step;
    const char* usage = "step N | step end | step back N | step hit | step start";
    if (n == 1 && args[0] == "end") c.step = StepMode::End;
    else if (n == 1 && args[0] == "hit") c.step = StepMode::Hit;
    else if (n == 1 && args[0] == "start") c.step = StepMode::Start;
    else if (n == 1) {
      c.step = StepMode::Forward;
      if (!parse_int(args[0], &c.ints[0]) || c.ints[0] < 0) return count_error(usage);
    } else if (n == 2 && args[0] == "back") {
      c.step = StepMode::Back;
      if (!parse_int(args[1], &c.ints[0]) || c.ints[0] < 0) return count_error(usage);
    } else {
      return count_error(usage);
    }
    return "";
  }
  if (verb == "build-step") {
    c.kind = CommandKind::BuildStep;
    const char* usage = "build-step N | build-step end | build-step back N | build-step start";
    if (n == 1 && args[0] == "end") c.step = StepMode::End;
    else if (n == 1 && args[0] == "start") c.step = StepMode::Start;
    else if (n == 1 && parse_int(args[0], &c.ints[0]) && c.ints[0] >= 0) c.step = StepMode::Forward;
    else if (n == 2 && args[0] == "back" && parse_int(args[1], &c.ints[0]) && c.ints[0] >= 0) c.step = StepMode::Back;
    else return count_error(usage);
    return "";
  }
  if (verb == "construct" || verb == "print-build-step") {
    c.kind = verb == "construct" ? CommandKind::Construct : CommandKind::PrintBuildStep;
    return n == 0 ? "" : "'" + verb + "' takes no arguments";
  }
  if (verb == "sah-plot") {
    c.kind = CommandKind::SahPlot;
    if (n != 1 || !parse_on_off(args[0], &c.on)) return count_error("sah-plot on|off");
    return "";
  }
  if (verb == "tree") {
    c.kind = CommandKind::Tree;
    if (n != 1 || !parse_on_off(args[0], &c.on)) return count_error("tree on|off");
    return "";
  }
  if (verb == "tree-select") {
    c.kind = CommandKind::TreeSelect;
    const char* usage = "tree-select NODE [isolate]";
    if (n < 1 || n > 2 || (n == 2 && args[1] != "isolate")) return count_error(usage);
    if (!parse_int(args[0], &c.ints[0]) || c.ints[0] < 0)
      return "tree-select: '" + args[0] + "' is not a node id (an integer >= 0)";
    c.on = n == 2;  // isolate
    return "";
  }
  if (verb == "show") {
    c.kind = CommandKind::Show;
    const char* usage = "show depth=A..B | show depth=A | show leaves | show all";
    if (n != 1) return count_error(usage);
    if (args[0] == "all") c.show = ShowMode::All;
    else if (args[0] == "leaves") c.show = ShowMode::Leaves;
    else if (args[0].starts_with("depth=")) {
      c.show = ShowMode::Depth;
      const std::string range = args[0].substr(6);
      const size_t dots = range.find("..");
      const std::string a = range.substr(0, dots), b = dots == std::string::npos ? a : range.substr(dots + 2);
      if (!parse_int(a, &c.ints[0]) || !parse_int(b, &c.ints[1]) || c.ints[0] < 0 || c.ints[1] < c.ints[0])
        return "show: '" + args[0] + "' is not depth=A..B with 0 <= A <= B";
    } else {
      return count_error(usage);
    }
    return "";
  }
  if (verb == "heatmap") {
    c.kind = CommandKind::Heatmap;
    if (n != 1 || (args[0] != "off" && args[0] != "nodes" && args[0] != "prims"))
      return count_error("heatmap off|nodes|prims");
    c.name = args[0];
    return "";
  }
  if (verb == "mesh") {
    c.kind = CommandKind::Mesh;
    if (n != 1 || (args[0] != "solid" && args[0] != "translucent" && args[0] != "wireframe" && args[0] != "off"))
      return count_error("mesh solid|translucent|wireframe|off");
    c.name = args[0];
    return "";
  }
  if (verb == "memory-limit") {
    c.kind = CommandKind::MemoryLimit;
    if (n != 1) return "usage: memory-limit SIZE (512M, 4G, 25%) or memory-limit default";
    if (args[0] == "default") return "";
    auto bytes = accel::parse_memory_size(args[0], "memory-limit");
    if (!bytes) return bytes.error().message;
    c.bytes = bytes.value();
    return "";
  }
  if (verb == "opacity") {
    c.kind = CommandKind::Opacity;
    if (n != 1 || !parse_finite(args[0], &c.values[0]) || c.values[0] < 0.05f || c.values[0] > 1.0f)
      return "usage: opacity A (a number in 0.05..1)";
    return "";
  }
  if (verb == "empty-cells" || verb == "large" || verb == "nodes") {
    c.kind = verb == "large" ? CommandKind::Large : verb == "nodes" ? CommandKind::Nodes : CommandKind::EmptyCells;
    if (n != 1 || !parse_on_off(args[0], &c.on)) return count_error((verb + " on|off").c_str());
    return "";
  }
  if (verb == "panel") {
    c.kind = CommandKind::Panel;
    const char* usage = "panel on|off | panel scene|ray|steps|code|compare|sweep|legend|vars|strip|trap on|off";
    if (n == 1 && parse_on_off(args[0], &c.on)) {
      c.name = "all";
      return "";
    }
    static const char* kPanels[] = {"all",     "scene", "ray",  "steps", "code", "compare",
                                    "sweep",   "legend", "vars", "strip", "trap"};
    if (n != 2 || !parse_on_off(args[1], &c.on)) return count_error(usage);
    for (const char* p : kPanels) {
      if (args[0] == p) {
        c.name = args[0];
        return "";
      }
    }
    return count_error(usage);
  }
  if (verb == "compare") {
    c.kind = CommandKind::Compare;
    return n == 0 ? "" : count_error("compare");
  }
  if (verb == "sweep") {
    c.kind = CommandKind::Sweep;
    const char* usage = "sweep PARAM LO HI STEPS";
    if (n != 4) return count_error(usage);
    c.name = args[0];
    float lo, hi;
    if (!parse_finite(args[1], &lo) || !parse_finite(args[2], &hi) || !parse_int(args[3], &c.ints[0]) ||
        c.ints[0] < 2 || c.ints[0] > 64 || !(lo < hi))
      return "sweep: expected PARAM LO HI STEPS with LO < HI and 2 <= STEPS <= 64";
    c.values[0] = lo;
    c.values[1] = hi;
    return "";
  }
  if (verb == "screenshot" || verb == "frames") {
    c.kind = verb == "screenshot" ? CommandKind::Screenshot : CommandKind::Frames;
    if (n != 1) return count_error(verb == "screenshot" ? "screenshot PATH" : "frames PREFIX");
    c.name = args[0];
    return "";
  }
  if (verb == "print-hit" || verb == "print-step" || verb == "print-ray" || verb == "print-stats") {
    c.kind = verb == "print-hit"    ? CommandKind::PrintHit
             : verb == "print-step" ? CommandKind::PrintStep
             : verb == "print-ray"  ? CommandKind::PrintRay
                                    : CommandKind::PrintStats;
    return n == 0 ? "" : "'" + verb + "' takes no arguments";
  }
  if (verb == "print-vars" || verb == "print-naive") {
    c.kind = verb == "print-vars" ? CommandKind::PrintVars : CommandKind::PrintNaive;
    return n == 0 ? "" : "'" + verb + "' takes no arguments";
  }
  if (verb == "trap") {
    c.kind = CommandKind::Trap;
    if (n != 1) return count_error("trap pq|kd|grid");
    if (auto demo = accel::trap_demo(args[0]); !demo) return "trap: " + demo.error().message;
    c.name = args[0];
    return "";
  }
  if (verb == "playlist") {
    c.kind = CommandKind::Playlist;
    if (n != 1) return count_error("playlist FILE");
    c.name = args[0];
    return "";
  }
  if (verb == "next" || verb == "prev" || verb == "print-state") {
    c.kind = verb == "next" ? CommandKind::Next : verb == "prev" ? CommandKind::Prev : CommandKind::PrintState;
    return n == 0 ? "" : "'" + verb + "' takes no arguments";
  }
  if (verb == "record") {
    const char* usage = "record PATH.gif|PATH.mp4 [fps=N] [ui=on|off] [size=WxH] | record stop";
    if (n == 1 && args[0] == "stop") {
      c.kind = CommandKind::RecordStop;
      return "";
    }
    c.kind = CommandKind::Record;
    if (n < 1) return count_error(usage);
    if (auto format = video_format_of(args[0]); !format) return "record: " + format.error().message;
    c.name = args[0];
    c.ints[0] = 4;
    c.on = true;
    for (size_t i = 1; i < n; ++i) {
      const std::string& a = args[i];
      int w = 0, h = 0;
      char x = 0, extra = 0;
      if (a.rfind("fps=", 0) == 0) {
        if (!parse_int(a.substr(4), &c.ints[0]) || c.ints[0] < 1 || c.ints[0] > 60)
          return "record: fps must be an integer in 1..60, got '" + a.substr(4) + "'";
      } else if (a.rfind("ui=", 0) == 0) {
        if (!parse_on_off(a.substr(3), &c.on)) return "record: ui must be on or off, got '" + a.substr(3) + "'";
      } else if (a.rfind("size=", 0) == 0) {
        if (std::sscanf(a.c_str() + 5, "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 16 ||
            h < 16 || w > 8192 || h > 8192)
          return "record: size must be WxH with W and H in 16..8192, got '" + a.substr(5) + "'";
        c.values[0] = static_cast<float>(w);
        c.values[1] = static_cast<float>(h);
      } else {
        return count_error(usage);
      }
    }
    return "";
  }
  if (verb == "heatmap-scale") {
    c.kind = CommandKind::HeatmapScale;
    const char* usage = "heatmap-scale auto | heatmap-scale LO HI";
    if (n == 1 && args[0] == "auto") {
      c.on = false;
      return "";
    }
    if (n != 2) return count_error(usage);
    if (std::string e = floats(0, 2, usage); !e.empty()) return "heatmap-scale: " + e;
    if (!(c.values[0] >= 0.0f && c.values[0] < c.values[1]))
      return "heatmap-scale: expected 0 <= LO < HI, got " + args[0] + " " + args[1];
    c.on = true;
    return "";
  }
  if (verb == "heatmap-diff") {
    c.kind = CommandKind::HeatmapDiff;
    if (n < 1) return count_error("heatmap-diff NAME [key=value ...] | heatmap-diff off");
    c.on = !(n == 1 && args[0] == "off");
    if (!c.on) return "";
    c.name = args[0];
    c.params.assign(args.begin() + 1, args.end());
    auto choice = accel::parse_structure(c.name, c.params);
    return choice ? "" : "heatmap-diff: " + choice.error().message;
  }
  if (verb == "print-heatmap") {
    c.kind = CommandKind::PrintHeatmap;
    return n == 0 ? "" : "'" + verb + "' takes no arguments";
  }
  if (verb == "colors") {
    c.kind = CommandKind::Colors;
    const char* usage = "colors viridis|cividis|turbo [hits=blue-orange|green-red]";
    Colormap map = Colormap::Viridis;
    if (n < 1 || n > 2 || !parse_colormap(args[0], &map)) return count_error(usage);
    c.name = args[0];
    c.on = true;  // hits=blue-orange
    if (n == 2) {
      if (args[1] == "hits=blue-orange") c.on = true;
      else if (args[1] == "hits=green-red") c.on = false;
      else return count_error(usage);
    }
    return "";
  }
  if (verb == "print-frame-time") {
    c.kind = CommandKind::PrintFrameTime;
    if (n != 1 || !parse_int(args[0], &c.ints[0]) || c.ints[0] < 1 || c.ints[0] > 10000)
      return count_error("print-frame-time N (1..10000 frames)");
    return "";
  }
  if (verb == "trace-rays") {
    c.kind = CommandKind::TraceRays;
    if (n != 1) return count_error("trace-rays random:N:SEED | primary:W:H | FILE");
    c.name = args[0];
    return "";
  }
  if (verb == "load-bench") {
    c.kind = CommandKind::LoadBench;
    if (n != 1) return count_error("load-bench FILE");
    c.name = args[0];
    return "";
  }
  if (verb == "show-chart") {
    c.kind = CommandKind::ShowChart;
    const char* usage = "show-chart on|off [x=errors|t-error] [speed=mt|1t] [y=linear|log] [labels=on|off] [group=N]";
    if (n < 1 || !parse_on_off(args[0], &c.on)) return count_error(usage);
    // The settings are checked here (group against the file only when it runs).
    ChartOptions check;
    for (size_t i = 1; i < n; ++i)
      if (std::string e = set_chart_option(check, args[i]); !e.empty()) return "show-chart: " + e;
    c.params.assign(args.begin() + 1, args.end());
    return "";
  }
  return "unknown command '" + verb + "'";
}

}  // namespace

std::string script_error(const std::string& script_name, int line, const std::string& message) {
  return script_name + ":" + std::to_string(line) + ": " + message;
}

accel::Result<std::vector<ScriptCommand>> parse_script(const std::string& text, const std::string& script_name) {
  std::vector<ScriptCommand> commands;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::vector<std::string> tokens = tokens_of(line);
    if (tokens.empty()) continue;
    ScriptCommand c;
    c.line = number;
    const std::vector<std::string> args(tokens.begin() + 1, tokens.end());
    const std::string error = parse_command(tokens[0], args, c);
    if (!error.empty()) return accel::make_error(script_error(script_name, number, error));
    commands.push_back(std::move(c));
  }
  return commands;
}

accel::Result<std::vector<ScriptCommand>> load_script(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return accel::make_error(path + ": cannot read the script");
  std::ostringstream text;
  text << file.rdbuf();
  return parse_script(text.str(), path);
}

}  // namespace viz
