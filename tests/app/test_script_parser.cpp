// The script parser: every command, its errors (naming script and line), the chart commands.
#include <cmath>
#include <gtest/gtest.h>

#include "script.h"
#include "script_verbs.h"
#include "viewer_test_support.h"

namespace viz {
namespace {


// ---------------------------------------------------------------------------------------
// Script parser

TEST(Script, ParsesEveryCommand) {
  const std::string text =
      "# a comment line\n"
      "size 800 600\n"
      "\n"
      "scene procedural:cornell   # trailing comment\n"
      "structure bvh traversal=pqueue leaf_size=2\n"
      "kernel moller\n"
      "camera 0 1 5 0 1 0 40\n"
      "camera 0 1 5 0 1 0\n"
      "ray-at-pixel 320 240\n"
      "ray 0x1p-2 0 5 0 0 -1\n"
      "step 3\n"
      "step end\n"
      "step back 2\n"
      "step hit\n"
      "show depth=2..4\n"
      "show depth=3\n"
      "show leaves\n"
      "show all\n"
      "heatmap prims\n"
      "mesh translucent\n"
      "empty-cells on\n"
      "nodes off\n"
      "opacity 0.4\n"
      "panel off\n"
      "panel code on\n"
      "large on\n"
      "compare\n"
      "sweep leaf_size 1 16 8\n"
      "screenshot out.png\n"
      "frames out/f_\n"
      "print-hit\nprint-step\nprint-ray\nprint-stats\nprint-frame-time 10\n"
      "preset stadium\n";
  auto parsed = parse_script(text, "t.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const auto& c = parsed.value();
  ASSERT_EQ(c.size(), 34u);
  EXPECT_EQ(c[0].verb, "size");
  EXPECT_EQ(c[0].line, 2);
  EXPECT_EQ(c[0].get<SizeArgs>().width, 800);
  EXPECT_EQ(c[0].get<SizeArgs>().height, 600);
  EXPECT_EQ(c[1].verb, "scene");
  EXPECT_EQ(c[1].get<Word>().word, "procedural:cornell");
  EXPECT_EQ(c[1].line, 4);
  EXPECT_EQ(c[2].verb, "structure");
  EXPECT_EQ(c[2].get<StructureArgs>().name, "bvh");
  EXPECT_EQ(c[2].get<StructureArgs>().params, (std::vector<std::string>{"traversal=pqueue", "leaf_size=2"}));
  EXPECT_EQ(c[3].verb, "kernel");
  EXPECT_EQ(c[3].get<KernelArgs>().kernel, accel::Kernel::Moller);
  EXPECT_EQ(c[4].verb, "camera");
  EXPECT_EQ(c[4].get<CameraArgs>().fovy_deg, 40.0f);
  EXPECT_EQ(c[4].get<CameraArgs>().eye.z, 5.0f);
  EXPECT_FALSE(c[5].get<CameraArgs>().fovy_deg);
  EXPECT_EQ(c[6].verb, "ray-at-pixel");
  EXPECT_EQ(c[6].get<PixelArgs>().x, 320.0f);
  EXPECT_EQ(c[7].verb, "ray");
  EXPECT_EQ(c[7].get<RayArgs>().ray.org.x, 0.25f);  // hex float
  EXPECT_EQ(c[7].get<RayArgs>().ray.dir.z, -1.0f);
  EXPECT_EQ(c[8].get<PlayerMove>().mode, StepMode::Forward);
  EXPECT_EQ(c[8].get<PlayerMove>().count, 3);
  EXPECT_EQ(c[9].get<PlayerMove>().mode, StepMode::End);
  EXPECT_EQ(c[10].get<PlayerMove>().mode, StepMode::Back);
  EXPECT_EQ(c[10].get<PlayerMove>().count, 2);
  EXPECT_EQ(c[11].get<PlayerMove>().mode, StepMode::Hit);
  EXPECT_EQ(c[12].get<ShowArgs>().mode, ShowMode::Depth);
  EXPECT_EQ(c[12].get<ShowArgs>().lo, 2);
  EXPECT_EQ(c[12].get<ShowArgs>().hi, 4);
  EXPECT_EQ(c[13].get<ShowArgs>().lo, 3);
  EXPECT_EQ(c[13].get<ShowArgs>().hi, 3);
  EXPECT_EQ(c[14].get<ShowArgs>().mode, ShowMode::Leaves);
  EXPECT_EQ(c[15].get<ShowArgs>().mode, ShowMode::All);
  EXPECT_EQ(c[16].verb, "heatmap");
  EXPECT_EQ(c[16].get<HeatmapArgs>().metric, accel::CostMetric::PrimsTested);
  EXPECT_EQ(c[17].get<Word>().word, "translucent");
  EXPECT_TRUE(c[18].get<OnOff>().on);
  EXPECT_EQ(c[19].verb, "nodes");
  EXPECT_FALSE(c[19].get<OnOff>().on);
  EXPECT_EQ(c[20].verb, "opacity");
  EXPECT_EQ(c[20].get<OpacityArgs>().alpha, 0.4f);
  EXPECT_EQ(c[21].get<PanelArgs>().panel, "all");
  EXPECT_FALSE(c[21].get<PanelArgs>().on);
  EXPECT_EQ(c[22].get<PanelArgs>().panel, "code");
  EXPECT_EQ(c[24].verb, "compare");
  EXPECT_EQ(c[25].verb, "sweep");
  EXPECT_EQ(c[25].get<SweepArgs>().param, "leaf_size");
  EXPECT_EQ(c[25].get<SweepArgs>().steps, 8);
  EXPECT_EQ(c[26].verb, "screenshot");
  EXPECT_EQ(c[27].verb, "frames");
  EXPECT_EQ(c[27].get<Word>().word, "out/f_");
  EXPECT_EQ(c[31].verb, "print-stats");
  EXPECT_EQ(c[32].get<FrameTimeArgs>().frames, 10);
  EXPECT_EQ(c[33].verb, "preset");
}

TEST(Script, ErrorsNameScriptAndLine) {
  struct Case {
    const char* text;
    const char* expected;  // substring of the message
  };
  const Case cases[] = {
      {"size 800 600\nfly away\n", "s.txt:2: unknown command 'fly'"},
      {"size 10 600\n", "s.txt:1: size: W and H must be integers in 64..8192"},
      {"size 800\n", "s.txt:1: usage: size W H"},
      {"\n\nstructure octopus\n", "s.txt:3: unknown structure 'octopus'"},
      {"structure bvh leaf_size=0\n", "s.txt:1: bvh parameter 'leaf_size' = '0' is invalid: expected an integer in [1, 64]"},
      {"structure bvh nonsense=1\n", "s.txt:1: unknown parameter 'nonsense'"},
      {"camera 0 0 0 1 1\n", "s.txt:1: usage: camera"},
      {"camera 0 0 0 1 1 1 200\n", "FOVY_DEG must be in (1, 170)"},
      {"camera 1 1 1 1 1 1\n", "eye and target are the same point"},
      {"ray 0 0 0 0 0 0\n", "ray: the direction is zero"},
      {"ray 0 0 nan 0 0 1\n", "'nan' is not a finite number"},
      {"ray-at-pixel 10 x\n", "'x' is not a finite number"},
      {"step sideways\n", "usage: step N"},
      {"step -3\n", "usage: step N"},
      {"show depth=4..2\n", "not depth=A..B"},
      {"heatmap hot\n", "usage: heatmap off|nodes|prims"},
      {"panel left on\n", "usage: panel"},
      {"print-hit now\n", "'print-hit' takes no arguments"},
      {"kernel fast\n", "usage: kernel"},
      {"sweep leaf_size 8 2 5\n", "LO < HI"},
      {"screenshot\n", "usage: screenshot PATH"},
      {"opacity 2\n", "usage: opacity A"},
      {"nodes maybe\n", "usage: nodes on|off"},
  };
  for (const Case& c : cases) {
    auto parsed = parse_script(c.text, "s.txt");
    ASSERT_FALSE(parsed.ok()) << c.text;
    EXPECT_NE(parsed.error().message.find(c.expected), std::string::npos)
        << "script: " << c.text << "\nmessage: " << parsed.error().message;
  }
  EXPECT_FALSE(load_script("/nonexistent/script.txt").ok());
  EXPECT_EQ(script_error("a.txt", 7, "boom"), "a.txt:7: boom");
}

TEST(Script, TreeCommands) {
  auto parsed = parse_script("tree on\ntree off\ntree-select 12\ntree-select 0 isolate\n", "t.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const std::vector<ScriptCommand>& c = parsed.value();
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0].verb, "tree");
  EXPECT_TRUE(c[0].get<OnOff>().on);
  EXPECT_EQ(c[1].verb, "tree");
  EXPECT_FALSE(c[1].get<OnOff>().on);
  EXPECT_EQ(c[2].verb, "tree-select");
  EXPECT_EQ(c[2].get<TreeSelectArgs>().node, 12);
  EXPECT_FALSE(c[2].get<TreeSelectArgs>().isolate);
  EXPECT_EQ(c[3].get<TreeSelectArgs>().node, 0);
  EXPECT_TRUE(c[3].get<TreeSelectArgs>().isolate);
  EXPECT_EQ(c[3].line, 4);
  struct Case {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
      {"tree\n", "t.txt:1: usage: tree on|off"},
      {"tree maybe\n", "usage: tree on|off"},
      {"tree-select\n", "usage: tree-select NODE [isolate]"},
      {"tree-select 3 alone\n", "usage: tree-select NODE [isolate]"},
      {"tree-select 3 isolate more\n", "usage: tree-select NODE [isolate]"},
      {"\ntree-select -1\n", "t.txt:2: tree-select: '-1' is not a node id"},
      {"tree-select root\n", "tree-select: 'root' is not a node id"},
      {"tree-select 99999999999\n", "is not a node id"},
  };
  for (const Case& k : cases) {
    auto bad = parse_script(k.text, "t.txt");
    ASSERT_FALSE(bad.ok()) << k.text;
    EXPECT_NE(bad.error().message.find(k.expected), std::string::npos) << bad.error().message;
  }
}

TEST(Script, LectureCommands) {
  // Traversal numbers, traps, playlist, recording.
  auto parsed = parse_script("print-vars\ntrap kd\nprint-naive\nplaylist talk.playlist\nnext\nprev\nprint-state\n"
                             "record a.gif\nrecord b.MP4 fps=12 ui=off size=640x360\nrecord stop\n",
                             "t.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const auto& c = parsed.value();
  ASSERT_EQ(c.size(), 10u);
  const char* verbs[] = {"print-vars", "trap", "print-naive", "playlist", "next", "prev", "print-state", "record",
                         "record", "record"};
  for (size_t i = 0; i < c.size(); ++i) EXPECT_EQ(c[i].verb, verbs[i]) << i;
  EXPECT_EQ(c[1].get<Word>().word, "kd");
  EXPECT_EQ(c[3].get<Word>().word, "talk.playlist");
  const RecordArgs& a = c[7].get<RecordArgs>();
  EXPECT_FALSE(a.stop);
  EXPECT_EQ(a.path, "a.gif");
  EXPECT_EQ(a.options.fps, 4) << "default fps";
  EXPECT_TRUE(a.options.ui) << "default ui=on";
  EXPECT_EQ(a.options.width, 0) << "default size: as captured";
  const RecordArgs& b = c[8].get<RecordArgs>();
  EXPECT_EQ(b.options.fps, 12);
  EXPECT_FALSE(b.options.ui);
  EXPECT_EQ(b.options.width, 640);
  EXPECT_EQ(b.options.height, 360);
  EXPECT_TRUE(c[9].get<RecordArgs>().stop);

  const std::pair<const char*, const char*> errors[] = {
      {"trap nope\n", "t.txt:1: trap: unknown trap 'nope' (valid: pq, kd, grid)"},
      {"trap\n", "usage: trap pq|kd|grid"},
      {"print-vars now\n", "'print-vars' takes no arguments"},
      {"next 2\n", "'next' takes no arguments"},
      {"playlist\n", "usage: playlist FILE"},
      {"record\n", "usage: record PATH.gif|PATH.mp4"},
      {"record clip.avi\n", "record: clip.avi: unknown recording format '.avi' (valid: .gif, .mp4)"},
      {"record a.gif fps=0\n", "record: fps must be an integer in 1..60, got '0'"},
      {"record a.gif fps=x\n", "record: fps must be an integer in 1..60"},
      {"record a.gif ui=maybe\n", "record: ui must be on or off"},
      {"record a.gif size=10x10\n", "record: size must be WxH with W and H in 16..8192"},
      {"record a.gif size=640x360x\n", "record: size must be WxH"},
      {"record a.gif speed=2\n", "usage: record PATH.gif|PATH.mp4"},
  };
  for (const auto& [text, expected] : errors) {
    auto bad = parse_script(text, "t.txt");
    ASSERT_FALSE(bad.ok()) << text;
    EXPECT_NE(bad.error().message.find(expected), std::string::npos) << bad.error().message;
  }
}

TEST(Script, BlackboardCommands) {
  auto parsed = parse_script(
      "mode 2d\nscene2d board.scene2d\nadd2d tri 0 0 1 0 0x1p-1 1\nray2d -1 0.5 1 0\nmode 3d\nsave2d b.scene2d\n", "b.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const auto& c = parsed.value();
  ASSERT_EQ(c.size(), 6u);
  EXPECT_EQ(c[5].verb, "save2d");
  EXPECT_EQ(c[5].get<Word>().word, "b.scene2d");
  EXPECT_EQ(c[0].verb, "mode");
  EXPECT_TRUE(c[0].get<Mode2dArgs>().planar);
  EXPECT_EQ(c[1].verb, "scene2d");
  EXPECT_EQ(c[1].get<Word>().word, "board.scene2d");
  EXPECT_EQ(c[2].verb, "add2d");
  EXPECT_EQ(c[2].get<Triangle2dArgs>().xy[4], 0.5f);
  EXPECT_EQ(c[2].get<Triangle2dArgs>().xy[5], 1.0f);
  EXPECT_EQ(c[3].verb, "ray2d");
  EXPECT_EQ(c[3].get<Ray2dArgs>().values[0], -1.0f);
  EXPECT_EQ(c[3].get<Ray2dArgs>().values[2], 1.0f);
  EXPECT_FALSE(c[4].get<Mode2dArgs>().planar);
  const std::pair<const char*, const char*> errors[] = {
      {"mode\n", "b.txt:1: usage: mode 2d|3d"},
      {"mode 4d\n", "usage: mode 2d|3d"},
      {"scene2d\n", "usage: scene2d FILE"},
      {"add2d 0 0 1 0 0 1\n", "usage: add2d tri X1 Y1 X2 Y2 X3 Y3"},
      {"add2d tri 0 0 1 0 0 nan\n", "'nan' is not a finite number (add2d tri X1 Y1 X2 Y2 X3 Y3)"},
      {"ray2d 0 0 1\n", "usage: ray2d OX OY DX DY"},
      {"ray2d 0 0 0 0\n", "ray2d: the direction is zero"},
      {"save2d\n", "usage: save2d FILE"},
  };
  for (const auto& [text, expected] : errors) {
    auto bad = parse_script(text, "b.txt");
    ASSERT_FALSE(bad.ok()) << text;
    EXPECT_NE(bad.error().message.find(expected), std::string::npos) << bad.error().message;
  }
}

TEST(Script, BenchChartCommands) {
  auto parsed = parse_script("load-bench out/bench.json\nshow-chart on x=t-error speed=1t y=log labels=off group=2\n"
                             "show-chart off\n",
                             "t.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const auto& c = parsed.value();
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].verb, "load-bench");
  EXPECT_EQ(c[0].get<Word>().word, "out/bench.json");
  EXPECT_EQ(c[1].verb, "show-chart");
  EXPECT_TRUE(c[1].get<ShowChartArgs>().on);
  EXPECT_EQ(c[1].get<ShowChartArgs>().settings,
            (std::vector<std::string>{"x=t-error", "speed=1t", "y=log", "labels=off", "group=2"}));
  EXPECT_EQ(c[2].verb, "show-chart");
  EXPECT_FALSE(c[2].get<ShowChartArgs>().on);

  const std::pair<const char*, const char*> errors[] = {
      {"load-bench\n", "t.txt:1: usage: load-bench FILE"},
      {"load-bench a.json b.json\n", "t.txt:1: usage: load-bench FILE"},
      {"show-chart\n", "t.txt:1: usage: show-chart on|off"},
      {"show-chart maybe\n", "t.txt:1: usage: show-chart on|off"},
      {"show-chart on x=speed\n", "t.txt:1: show-chart: x: expected errors or t-error, got 'speed'"},
      {"show-chart on group=0\n", "t.txt:1: show-chart: group: expected a group number from 1, got '0'"},
      {"show-chart on colour=red\n", "t.txt:1: show-chart: unknown chart setting 'colour=red'"},
  };
  for (const auto& [text, expected] : errors) {
    auto bad = parse_script(text, "t.txt");
    ASSERT_FALSE(bad.ok()) << text;
    EXPECT_NE(bad.error().message.find(expected), std::string::npos) << bad.error().message;
  }
}

TEST(Script, StateCommands) {
  // What accelviz-cli check's replay files and save-state write: a ray with its tmin and tmax
  // (hex floats, tmax inf), and the state saved to a file.
  auto parsed = parse_script("ray 0x1p-1 0 3 0 0 -0x1p+0 0x1p-2 inf\nray 0 0 3 0 0 -1 0 2.5\nray 0 0 3 0 0 -1\n"
                             "save-state s.state\n",
                             "s.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const auto& c = parsed.value();
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0].verb, "ray");
  EXPECT_EQ(c[0].get<RayArgs>().ray.org.x, 0.5f);
  EXPECT_EQ(c[0].get<RayArgs>().ray.dir.z, -1.0f);
  EXPECT_EQ(c[0].get<RayArgs>().ray.tmin, 0.25f);
  EXPECT_TRUE(std::isinf(c[0].get<RayArgs>().ray.tmax));
  EXPECT_EQ(c[1].get<RayArgs>().ray.tmax, 2.5f);
  EXPECT_EQ(c[2].get<RayArgs>().ray.tmin, 0.0f);  // without them: [0, inf)
  EXPECT_TRUE(std::isinf(c[2].get<RayArgs>().ray.tmax));
  EXPECT_EQ(c[3].verb, "save-state");
  EXPECT_EQ(c[3].get<Word>().word, "s.state");
  const std::pair<const char*, const char*> errors[] = {
      {"ray 0 0 3 0 0 -1 0\n", "usage: ray OX OY OZ DX DY DZ [TMIN TMAX]"},
      {"ray 0 0 3 0 0 -1 2 1\n", "ray: TMIN is greater than TMAX"},
      {"ray 0 0 3 0 0 -1 inf inf\n", "'inf' is not a finite number"},
      {"ray 0 0 3 0 0 -1 0 nan\n", "'nan' is not a number or inf"},
      {"save-state\n", "usage: save-state FILE"},
  };
  for (const auto& [text, expected] : errors) {
    auto bad = parse_script(text, "s.txt");
    ASSERT_FALSE(bad.ok()) << text;
    EXPECT_NE(bad.error().message.find(expected), std::string::npos) << bad.error().message;
  }
}

TEST(Script, FailedBuildReplay) {
  // A failed build's state as accelviz-cli check writes it: the structure line gets the N of
  // the construct-until after it (its build stops there too), the construct-until check's
  // comment lines; a structure line after it builds whole again.
  auto parsed = parse_script("# accelviz-cli check: s, hard/c: build threw: std::bad_alloc\n"
                             "  #   at node 3 (depth 1)\n"
                             "scene procedural:soup\nstructure bvh\n# not a header line\n"
                             "construct-until 123456789012\nstructure bvh\n",
                             "f.state");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  const auto& c = parsed.value();
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[1].get<StructureArgs>().calls, 123456789012u);
  EXPECT_EQ(c[2].verb, "construct-until");
  EXPECT_EQ(c[2].get<ConstructUntilArgs>().calls, 123456789012u);
  EXPECT_EQ(c[2].get<ConstructUntilArgs>().header,
            (std::vector<std::string>{"accelviz-cli check: s, hard/c: build threw: std::bad_alloc",
                                      "at node 3 (depth 1)"}));
  EXPECT_EQ(c[3].get<StructureArgs>().calls, 0u);
  // A script of its own: no structure line to bind, and its comments are not check's.
  parsed = parse_script("# my replay\nconstruct-until 5\n", "g.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  EXPECT_EQ(parsed.value()[0].get<ConstructUntilArgs>().calls, 5u);
  EXPECT_TRUE(parsed.value()[0].get<ConstructUntilArgs>().header.empty());
  for (const char* text : {"construct-until 0\n", "construct-until -3\n", "construct-until 1e3\n",
                           "construct-until\n", "construct-until 99999999999999999999999\n"}) {
    auto bad = parse_script(text, "h.txt");
    ASSERT_FALSE(bad.ok()) << text;
    EXPECT_TRUE(bad.error().message.find("construct-until") != std::string::npos) << bad.error().message;
  }
}

}  // namespace
}  // namespace viz
