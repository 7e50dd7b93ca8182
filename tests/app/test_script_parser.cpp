// The script parser: every command, its errors (naming script and line), the chart commands.
#include <cmath>
#include <gtest/gtest.h>

#include "script.h"
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
  EXPECT_EQ(c[0].kind, CommandKind::Size);
  EXPECT_EQ(c[0].line, 2);
  EXPECT_EQ(c[0].ints[0], 800);
  EXPECT_EQ(c[0].ints[1], 600);
  EXPECT_EQ(c[1].kind, CommandKind::Scene);
  EXPECT_EQ(c[1].name, "procedural:cornell");
  EXPECT_EQ(c[1].line, 4);
  EXPECT_EQ(c[2].kind, CommandKind::Structure);
  EXPECT_EQ(c[2].name, "bvh");
  EXPECT_EQ(c[2].params, (std::vector<std::string>{"traversal=pqueue", "leaf_size=2"}));
  EXPECT_EQ(c[3].kind, CommandKind::Kernel);
  EXPECT_EQ(c[4].kind, CommandKind::Camera);
  EXPECT_TRUE(c[4].has_fov);
  EXPECT_EQ(c[4].values[6], 40.0f);
  EXPECT_FALSE(c[5].has_fov);
  EXPECT_EQ(c[6].kind, CommandKind::RayAtPixel);
  EXPECT_EQ(c[6].values[0], 320.0f);
  EXPECT_EQ(c[7].kind, CommandKind::Ray);
  EXPECT_EQ(c[7].values[0], 0.25f);  // hex float
  EXPECT_EQ(c[7].values[5], -1.0f);
  EXPECT_EQ(c[8].step, StepMode::Forward);
  EXPECT_EQ(c[8].ints[0], 3);
  EXPECT_EQ(c[9].step, StepMode::End);
  EXPECT_EQ(c[10].step, StepMode::Back);
  EXPECT_EQ(c[10].ints[0], 2);
  EXPECT_EQ(c[11].step, StepMode::Hit);
  EXPECT_EQ(c[12].show, ShowMode::Depth);
  EXPECT_EQ(c[12].ints[0], 2);
  EXPECT_EQ(c[12].ints[1], 4);
  EXPECT_EQ(c[13].ints[0], 3);
  EXPECT_EQ(c[13].ints[1], 3);
  EXPECT_EQ(c[14].show, ShowMode::Leaves);
  EXPECT_EQ(c[15].show, ShowMode::All);
  EXPECT_EQ(c[16].kind, CommandKind::Heatmap);
  EXPECT_EQ(c[16].name, "prims");
  EXPECT_EQ(c[17].name, "translucent");
  EXPECT_TRUE(c[18].on);
  EXPECT_EQ(c[19].kind, CommandKind::Nodes);
  EXPECT_FALSE(c[19].on);
  EXPECT_EQ(c[20].kind, CommandKind::Opacity);
  EXPECT_EQ(c[20].values[0], 0.4f);
  EXPECT_EQ(c[21].name, "all");
  EXPECT_FALSE(c[21].on);
  EXPECT_EQ(c[22].name, "code");
  EXPECT_EQ(c[24].kind, CommandKind::Compare);
  EXPECT_EQ(c[25].kind, CommandKind::Sweep);
  EXPECT_EQ(c[25].name, "leaf_size");
  EXPECT_EQ(c[25].ints[0], 8);
  EXPECT_EQ(c[26].kind, CommandKind::Screenshot);
  EXPECT_EQ(c[27].kind, CommandKind::Frames);
  EXPECT_EQ(c[27].name, "out/f_");
  EXPECT_EQ(c[31].kind, CommandKind::PrintStats);
  EXPECT_EQ(c[32].ints[0], 10);
  EXPECT_EQ(c[33].kind, CommandKind::Preset);
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
  EXPECT_EQ(c[0].kind, CommandKind::Tree);
  EXPECT_TRUE(c[0].on);
  EXPECT_EQ(c[1].kind, CommandKind::Tree);
  EXPECT_FALSE(c[1].on);
  EXPECT_EQ(c[2].kind, CommandKind::TreeSelect);
  EXPECT_EQ(c[2].ints[0], 12);
  EXPECT_FALSE(c[2].on);  // not isolated
  EXPECT_EQ(c[3].ints[0], 0);
  EXPECT_TRUE(c[3].on);
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
  const CommandKind kinds[] = {CommandKind::PrintVars, CommandKind::Trap,  CommandKind::PrintNaive,
                               CommandKind::Playlist,  CommandKind::Next,  CommandKind::Prev,
                               CommandKind::PrintState, CommandKind::Record, CommandKind::Record,
                               CommandKind::RecordStop};
  for (size_t i = 0; i < c.size(); ++i) EXPECT_EQ(c[i].kind, kinds[i]) << i;
  EXPECT_EQ(c[1].name, "kd");
  EXPECT_EQ(c[3].name, "talk.playlist");
  EXPECT_EQ(c[7].name, "a.gif");
  EXPECT_EQ(c[7].ints[0], 4) << "default fps";
  EXPECT_TRUE(c[7].on) << "default ui=on";
  EXPECT_EQ(c[7].values[0], 0.0f) << "default size: as captured";
  EXPECT_EQ(c[8].ints[0], 12);
  EXPECT_FALSE(c[8].on);
  EXPECT_EQ(c[8].values[0], 640.0f);
  EXPECT_EQ(c[8].values[1], 360.0f);

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
  EXPECT_EQ(c[5].kind, CommandKind::Save2d);
  EXPECT_EQ(c[5].name, "b.scene2d");
  EXPECT_EQ(c[0].kind, CommandKind::Mode);
  EXPECT_TRUE(c[0].on);
  EXPECT_EQ(c[1].kind, CommandKind::Scene2d);
  EXPECT_EQ(c[1].name, "board.scene2d");
  EXPECT_EQ(c[2].kind, CommandKind::Add2d);
  EXPECT_EQ(c[2].values[4], 0.5f);
  EXPECT_EQ(c[2].values[5], 1.0f);
  EXPECT_EQ(c[3].kind, CommandKind::Ray2d);
  EXPECT_EQ(c[3].values[0], -1.0f);
  EXPECT_EQ(c[3].values[2], 1.0f);
  EXPECT_FALSE(c[4].on);
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
  EXPECT_EQ(c[0].kind, CommandKind::LoadBench);
  EXPECT_EQ(c[0].name, "out/bench.json");
  EXPECT_EQ(c[1].kind, CommandKind::ShowChart);
  EXPECT_TRUE(c[1].on);
  EXPECT_EQ(c[1].params, (std::vector<std::string>{"x=t-error", "speed=1t", "y=log", "labels=off", "group=2"}));
  EXPECT_EQ(c[2].kind, CommandKind::ShowChart);
  EXPECT_FALSE(c[2].on);

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
  EXPECT_EQ(c[0].kind, CommandKind::Ray);
  EXPECT_EQ(c[0].values[0], 0.5f);
  EXPECT_EQ(c[0].values[5], -1.0f);
  EXPECT_EQ(c[0].values[6], 0.25f);
  EXPECT_TRUE(std::isinf(c[0].values[7]));
  EXPECT_EQ(c[1].values[7], 2.5f);
  EXPECT_EQ(c[2].values[6], 0.0f);  // without them: [0, inf)
  EXPECT_TRUE(std::isinf(c[2].values[7]));
  EXPECT_EQ(c[3].kind, CommandKind::SaveState);
  EXPECT_EQ(c[3].name, "s.state");
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
  EXPECT_EQ(c[1].calls, 123456789012u);
  EXPECT_EQ(c[2].kind, CommandKind::ConstructUntil);
  EXPECT_EQ(c[2].calls, 123456789012u);
  EXPECT_EQ(c[2].params, (std::vector<std::string>{"accelviz-cli check: s, hard/c: build threw: std::bad_alloc",
                                                   "at node 3 (depth 1)"}));
  EXPECT_EQ(c[3].calls, 0u);
  // A script of its own: no structure line to bind, and its comments are not check's.
  parsed = parse_script("# my replay\nconstruct-until 5\n", "g.txt");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  EXPECT_EQ(parsed.value()[0].calls, 5u);
  EXPECT_TRUE(parsed.value()[0].params.empty());
  for (const char* text : {"construct-until 0\n", "construct-until -3\n", "construct-until 1e3\n",
                           "construct-until\n", "construct-until 99999999999999999999999\n"}) {
    auto bad = parse_script(text, "h.txt");
    ASSERT_FALSE(bad.ok()) << text;
    EXPECT_TRUE(bad.error().message.find("construct-until") != std::string::npos) << bad.error().message;
  }
}

}  // namespace
}  // namespace viz
