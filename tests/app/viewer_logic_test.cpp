// The viewer's interaction logic without a window: the script parser, the camera model
// behind picking, the pseudo-code mapping of real traces, structure -> instances, the debug
// ray's replay after a rebuild, the compare / sweep work, and the bench chart's model
// (loading the JSON, axes, zero band). (TracePlayer itself is tested in
// tests/test_trace_player.cpp.)
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <map>
#include <set>

#include "bench_chart.h"
#include "camera.h"
#include "pseudo_code.h"
#include "ray_gen.h"
#include "registry.h"
#include "script.h"
#include "structure_view.h"
#include "workbench.h"

namespace viz {
namespace {

std::shared_ptr<const accel::Scene> scene_of(const std::string& name) {
  auto s = accel::make_procedural_scene(name);
  EXPECT_TRUE(s.ok());
  return std::make_shared<const accel::Scene>(std::move(s.value()));
}

accel::Ray sphere_ray() {
  accel::Ray r;
  r.org = accel::Vec3(0.13f, 0.21f, 5.0f);
  r.dir = glm::normalize(accel::Vec3(-0.02f, -0.03f, -1.0f));
  return r;
}

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

// ---------------------------------------------------------------------------------------
// Camera model: picking equals rendering

TEST(CameraModel, PixelRayRoundTrip) {
  Camera cam;
  accel::Aabb box;
  box.min = glm::vec3(-1.0f, 0.0f, -1.0f);
  box.max = glm::vec3(1.0f, 2.0f, 1.0f);
  const int w = 1280, h = 720;
  cam.frame(box, float(w) / float(h));
  cam.orbit(37.0f, -12.0f);
  const accel::PinholeCamera pin = cam.pinhole();
  EXPECT_NEAR(glm::length(pin.eye - cam.eye()), 0.0f, 1e-5f);
  for (const glm::vec2 px : {glm::vec2(0.5f, 0.5f), glm::vec2(640.0f, 360.0f), glm::vec2(1200.25f, 33.75f),
                             glm::vec2(17.0f, 700.0f)}) {
    const accel::Ray ray = accel::camera_ray(pin, px.x, px.y, w, h);
    for (float t : {1.0f, 3.0f, 7.5f}) {
      // The rendered position of a point on the ray is the pixel the ray was shot through.
      const glm::vec3 p = cam.project(ray.at(t), w, h);
      EXPECT_NEAR(p.x, px.x, 0.05f) << px.x << "," << px.y << " t=" << t;
      EXPECT_NEAR(p.y, px.y, 0.05f) << px.x << "," << px.y << " t=" << t;
    }
  }
  // The centre pixel's ray is the view direction.
  const accel::Ray centre = accel::camera_ray(pin, 0.5f * w, 0.5f * h, w, h);
  EXPECT_NEAR(glm::dot(centre.dir, glm::normalize(cam.target() - cam.eye())), 1.0f, 1e-5f);
}

TEST(CameraModel, LookAtReproducesTheView) {
  Camera cam;
  accel::Aabb box;
  box.min = glm::vec3(-100.0f);
  box.max = glm::vec3(100.0f);
  cam.look_at({2.4f, 1.7f, 3.2f}, {0.0f, 0.45f, 0.0f}, 40.0f, box);
  const accel::PinholeCamera pin = cam.pinhole();
  EXPECT_NEAR(glm::length(pin.eye - glm::vec3(2.4f, 1.7f, 3.2f)), 0.0f, 1e-4f);
  EXPECT_NEAR(glm::length(pin.target - glm::vec3(0.0f, 0.45f, 0.0f)), 0.0f, 1e-6f);
  EXPECT_NEAR(pin.fovy_deg, 40.0f, 1e-4f);
  // The target projects to the image centre.
  const glm::vec3 c = cam.project(pin.target, 800, 600);
  EXPECT_NEAR(c.x, 400.0f, 0.01f);
  EXPECT_NEAR(c.y, 300.0f, 0.01f);
}

// ---------------------------------------------------------------------------------------
// Pseudo code: every event of every real traversal maps to a line

TEST(PseudoCode, EveryEventOfEveryTraversalHasALine) {
  auto scene = scene_of("cornell");
  std::vector<accel::Ray> rays = accel::random_rays(scene->bounds(), 24, 7);
  rays.push_back(sphere_ray());
  accel::Ray miss;
  miss.org = glm::vec3(10.0f, 10.0f, 10.0f);
  miss.dir = glm::vec3(0.0f, 1.0f, 0.0f);
  rays.push_back(miss);
  for (const auto& info : accel::structure_registry()) {
    std::vector<std::string> traversals = {""};
    for (const auto& spec : info.params)
      if (spec.name == "traversal") traversals = spec.choices;
    for (const std::string& t : traversals) {
      StructureRequest req;
      req.name = info.name;
      if (!t.empty()) req.params = {"traversal=" + t};
      auto built = build_structure_now(scene, req);
      ASSERT_TRUE(built.ok()) << built.error().message;
      const BuiltStructure& b = *built.value();
      ASSERT_NE(b.kind, TraversalKind::Unknown) << info.name;
      const PseudoCode& code = pseudo_code(b.kind);
      ASSERT_EQ(code.lines.size(), code.anchors.size());
      std::set<std::string> anchors_seen;
      for (const accel::Ray& ray : rays) {
        accel::TraceRecorder rec;
        b.structure->intersect_traced(ray, rec);
        const NodeLookup lookup = [&b](accel::NodeId id) { return b.structure->node_view(id); };
        for (size_t i = 0; i < rec.events().size(); ++i) {
          const int line = pseudo_code_line(b.kind, rec.events(), i, lookup);
          EXPECT_GE(line, 0) << info.name << " " << t << ": " << accel::describe_event(rec.events()[i]);
          if (line >= 0) anchors_seen.insert(code.anchors[size_t(line)]);
        }
      }
      // The loop's core lines are reached.
      EXPECT_TRUE(anchors_seen.count("test")) << info.name << " " << t;
      EXPECT_TRUE(anchors_seen.count("closest")) << info.name << " " << t;
    }
  }
}

TEST(PseudoCode, KdTreeCasesAndGridAxes) {
  using accel::TraceEvent;
  using accel::TraceEventKind;
  auto ev = [](TraceEventKind k, accel::NodeId n, float t0, float t1) {
    TraceEvent e;
    e.kind = k;
    e.node = n;
    e.t0 = t0;
    e.t1 = t1;
    return e;
  };
  // Visit [1, 2]; skipped child with t_split 3 > t_max: case (b); t_split 0.5 < t_min: (c).
  std::vector<TraceEvent> b = {ev(TraceEventKind::Visit, 0, 1, 2), ev(TraceEventKind::Cull, 2, 3, 3)};
  std::vector<TraceEvent> c = {ev(TraceEventKind::Visit, 0, 1, 2), ev(TraceEventKind::Cull, 1, 0.5f, 0.5f)};
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::KdTree, b, 1, {}), "case_b");
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::KdTree, c, 1, {}), "case_c");
  std::vector<TraceEvent> a = {ev(TraceEventKind::Visit, 0, 1, 2), ev(TraceEventKind::Push, 2, 1.5f, 1.5f)};
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::KdTree, a, 1, {}), "case_a");
  std::vector<TraceEvent> root_miss = {ev(TraceEventKind::Cull, 0, 0, 0)};
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::KdTree, root_miss, 0, {}), "root");

  // Grid: the axis stepped between two cells, from their boxes.
  auto cell = [](accel::NodeId id) {
    accel::NodeView v;
    v.id = id;
    const int x = int(id % 4), y = int(id / 4 % 4), z = int(id / 16);
    v.box.min = glm::vec3(float(x), float(y), float(z));
    v.box.max = v.box.min + glm::vec3(1.0f);
    return v;
  };
  std::vector<TraceEvent> walk = {ev(TraceEventKind::EnterCell, 0, 0, 1), ev(TraceEventKind::EnterCell, 1, 1, 2),
                                  ev(TraceEventKind::EnterCell, 5, 2, 3), ev(TraceEventKind::EnterCell, 21, 3, 4)};
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::Grid, walk, 0, cell), "enter_first");
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::Grid, walk, 1, cell), "step_x");
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::Grid, walk, 2, cell), "step_y");
  EXPECT_EQ(pseudo_code_anchor(TraversalKind::Grid, walk, 3, cell), "step_z");
  EXPECT_EQ(traversal_kind("bvh", "pqueue"), TraversalKind::HierarchyPqueue);
  EXPECT_EQ(traversal_kind("spheretree", ""), TraversalKind::HierarchyOrdered);
  EXPECT_EQ(traversal_kind("nope", ""), TraversalKind::Unknown);
}

// ---------------------------------------------------------------------------------------
// Structure -> instances

TEST(StructureGeometry, OneInstancePerNode) {
  auto scene = scene_of("sphere");
  for (const auto& info : accel::structure_registry()) {
    StructureRequest req;
    req.name = info.name;
    auto built = build_structure_now(scene, req);
    ASSERT_TRUE(built.ok()) << built.error().message;
    const BuiltStructure& b = *built.value();
    size_t listed = 0, inner_with_plane = 0;
    b.structure->for_each_node([&](const accel::NodeView& v) {
      ++listed;
      if (v.split_axis >= 0) ++inner_with_plane;
    });
    const StructureGeometry& g = b.geometry;
    EXPECT_EQ(g.nodes, listed) << info.name;
    EXPECT_EQ(g.boxes.size() + g.spheres.size(), listed) << info.name;
    EXPECT_EQ(g.planes.size(), inner_with_plane) << info.name;
    if (info.name == "spheretree") {
      EXPECT_EQ(g.spheres.size(), listed);
    }
    if (info.name == "kdtree") {
      EXPECT_GT(g.planes.size(), 0u);
    }
    EXPECT_EQ(g.max_depth, b.stats.max_depth) << info.name;
    for (const NodeInstance& n : g.planes) {
      const int axis = int(n.axis);
      EXPECT_EQ(n.lo[axis], n.hi[axis]);  // flat along its axis
    }
  }
}

TEST(StructureGeometry, GridEmptyCellsOnRequest) {
  auto scene = scene_of("stadium");
  StructureRequest req;
  req.name = "grid";
  req.params = {"res=8,4,8"};
  auto sparse = build_structure_now(scene, req);
  ASSERT_TRUE(sparse.ok());
  req.geometry.empty_cells = true;
  auto all = build_structure_now(scene, req);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all.value()->geometry.boxes.size(), 8u * 4u * 8u);
  EXPECT_TRUE(all.value()->geometry.empty_cells_listed);
  EXPECT_LT(sparse.value()->geometry.boxes.size(), all.value()->geometry.boxes.size());
  EXPECT_TRUE(all.value()->geometry.uniform_depth);
  req.geometry.max_empty_cells = 10;  // too many: only the occupied cells
  auto capped = build_structure_now(scene, req);
  ASSERT_TRUE(capped.ok());
  EXPECT_TRUE(capped.value()->geometry.empty_cells_too_many);
  EXPECT_EQ(capped.value()->geometry.boxes.size(), sparse.value()->geometry.boxes.size());
}

TEST(StructureGeometry, UnitShapesAndColourMap) {
  EXPECT_EQ(unit_cube_edges().size(), 24u);
  EXPECT_EQ(unit_sphere_circles(16).size(), 3u * 16u * 2u);
  EXPECT_EQ(unit_square_triangles().size(), 6u);
  for (const glm::vec3& p : unit_sphere_circles(16)) EXPECT_NEAR(glm::length(p), 1.0f, 1e-5f);
  const glm::vec3 lo = turbo(0.15f), hi = turbo(0.95f), mid = turbo(0.5f);
  EXPECT_GT(lo.b, lo.r);   // blue end
  EXPECT_GT(hi.r, hi.b);   // red end
  EXPECT_GT(mid.g, 0.8f);  // green-yellow middle
  std::vector<Segment> segs;
  accel::Aabb box;
  box.min = glm::vec3(0.0f);
  box.max = glm::vec3(1.0f);
  append_box_segments(segs, box, glm::vec4(1.0f), 2.0f);
  EXPECT_EQ(segs.size(), 12u);
  append_box_segments(segs, accel::Aabb{}, glm::vec4(1.0f), 2.0f);  // empty: nothing
  EXPECT_EQ(segs.size(), 12u);
}

// ---------------------------------------------------------------------------------------
// Debug ray, compare, sweep

TEST(Workbench, BuildErrorsNameTheParameter) {
  auto scene = scene_of("sphere");
  StructureRequest req;
  req.name = "bvh";
  req.params = {"leaf_size=500"};
  auto built = build_structure_now(scene, req);
  ASSERT_FALSE(built.ok());
  EXPECT_NE(built.error().message.find("leaf_size"), std::string::npos);
  req.name = "nope";
  req.params = {};
  EXPECT_FALSE(build_structure_now(scene, req).ok());
  EXPECT_EQ(with_param({"a=1", "b=2"}, "b", "3"), (std::vector<std::string>{"a=1", "b=3"}));
  EXPECT_EQ(with_param({"a=1"}, "c", "x"), (std::vector<std::string>{"a=1", "c=x"}));
  EXPECT_EQ(param_value({"a=1", "traversal=dfs"}, "traversal"), "dfs");
  EXPECT_EQ(param_value({"a=1"}, "traversal", "ordered"), "ordered");
}

TEST(Workbench, RayReplayAfterRebuildKeepsTheStep) {
  auto scene = scene_of("sphere");
  StructureRequest req;
  req.name = "bvh";
  req.params = {"leaf_size=16"};
  auto coarse = build_structure_now(scene, req);
  req.params = {"leaf_size=1", "traversal=pqueue"};
  auto fine = build_structure_now(scene, req);
  ASSERT_TRUE(coarse.ok() && fine.ok());
  DebugRay ray;
  ray.active = true;
  ray.ray = sphere_ray();
  ray.record(*coarse.value()->structure, false);
  ASSERT_TRUE(ray.hit.valid());
  const accel::Hit first = ray.hit;
  ray.player.jump_to_end();
  const size_t old_step = ray.player.step();
  ray.record(*fine.value()->structure, true);  // the rebuild
  EXPECT_EQ(ray.hit.prim, first.prim);
  EXPECT_EQ(ray.hit.t, first.t);
  EXPECT_EQ(ray.player.step(), std::min(old_step, ray.player.size() - 1));
  ray.player.seek(3);
  ray.record(*coarse.value()->structure, true);
  EXPECT_EQ(ray.player.step(), 3u);
  ray.record(*coarse.value()->structure, false);  // a new ray starts over
  EXPECT_EQ(ray.player.step(), 0u);
  EXPECT_NEAR(ray_draw_length(ray.ray, ray.hit, scene->bounds()), ray.hit.t, 0.0f);
  accel::Hit none;
  EXPECT_GT(ray_draw_length(ray.ray, none, scene->bounds()), 5.0f);  // through the whole box
}

TEST(Workbench, CompareRunsEveryStructureAndTraversalOnOneRay) {
  auto scene = scene_of("sphere");
  StructureRequest current;
  current.name = "bvh";
  current.params = {"leaf_size=2", "traversal=dfs"};
  std::atomic<bool> cancel{false};
  std::atomic<int> progress{0};
  const auto rows = compare_structures(scene, sphere_ray(), current, cancel, &progress);
  // brute, grid, octree, kdtree, bvh x 3 traversals, spheretree x 3.
  ASSERT_EQ(rows.size(), 10u);
  EXPECT_EQ(progress.load(), 10);
  const accel::Hit reference = rows.front().hit;
  ASSERT_TRUE(reference.valid());
  int current_rows = 0;
  std::set<std::string> labels;
  for (const CompareRow& r : rows) {
    ASSERT_TRUE(r.ok) << r.label << ": " << r.error;
    EXPECT_EQ(r.hit.prim, reference.prim) << r.label;
    EXPECT_NEAR(r.hit.t, reference.t, 1e-4f * reference.t) << r.label;
    EXPECT_GT(r.steps, 0u);
    EXPECT_GT(r.stats.prims_tested, 0u);
    labels.insert(r.label);
    if (r.current) {
      ++current_rows;
      EXPECT_EQ(r.label, "bvh (dfs)");
      EXPECT_EQ(param_value(r.params, "leaf_size"), "2");  // the current parameters kept
    }
  }
  EXPECT_EQ(current_rows, 1);
  EXPECT_TRUE(labels.count("bvh (pqueue)"));
  EXPECT_TRUE(labels.count("spheretree (ordered)"));
  // Brute force tests every triangle.
  EXPECT_EQ(rows.front().stats.prims_tested, scene->valid_prims().size());
  cancel = true;
  EXPECT_TRUE(compare_structures(scene, sphere_ray(), current, cancel).front().error.empty());
}

TEST(Workbench, SweepValuesAndRun) {
  accel::ParamSpec leaf{"leaf_size", accel::ParamSpec::Type::Int, "4", 1, 64, {}, ""};
  EXPECT_EQ(sweep_values(leaf, 1, 16, 5, true), (std::vector<double>{1, 2, 4, 8, 16}));
  EXPECT_EQ(sweep_values(leaf, 1, 3, 10, false), (std::vector<double>{1, 2, 3}));  // rounded, no duplicates
  EXPECT_EQ(sweep_values(leaf, 0, 1000, 2, false), (std::vector<double>{1, 64}));   // clamped to the range
  accel::ParamSpec lambda{"lambda", accel::ParamSpec::Type::Float, "2", 0.01, 16, {}, ""};
  const auto v = sweep_values(lambda, 0.5, 4.0, 4, false);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_DOUBLE_EQ(v[1], 0.5 + 3.5 / 3.0);

  auto scene = scene_of("sphere");
  SweepRequest r;
  r.base.name = "grid";
  r.param = "lambda";
  r.lo = 0.5;
  r.hi = 2.0;
  r.steps = 3;
  r.camera = accel::default_camera(scene->bounds());
  r.width = 16;
  r.height = 12;
  SweepProgress progress;
  std::atomic<bool> cancel{false};
  ASSERT_TRUE(run_sweep(scene, r, progress, cancel).ok());
  ASSERT_EQ(progress.points.size(), 3u);
  EXPECT_EQ(progress.total, 3);
  for (const SweepPoint& p : progress.points) {
    EXPECT_TRUE(p.ok) << p.error;
    EXPECT_GE(p.build_ms, 0.0);
    EXPECT_GT(p.trace_ms, 0.0);
    EXPECT_GT(p.nodes, 0u);
  }
  EXPECT_LT(progress.points.front().nodes, progress.points.back().nodes);  // more cells with lambda
  r.param = "insert";  // a choice: not sweepable
  EXPECT_FALSE(run_sweep(scene, r, progress, cancel).ok());
}

// ---------------------------------------------------------------------------------------
// Bench chart: loading, validation, axes, the zero band, groups

/// One bench row as the CLI writes it, with `changes` (key -> JSON literal, or "" to drop
/// the key) applied.
std::string bench_row(const std::map<std::string, std::string>& changes = {}) {
  std::map<std::string, std::string> fields = {
      {"scene", "\"procedural:cornell\""}, {"structure", "\"bvh\""}, {"params", "\"\""},
      {"kernel", "\"watertight\""}, {"rays", "\"random:2000:1\""}, {"n_rays", "2000"},
      {"build_ms", "0.6"}, {"memory_bytes", "13936"}, {"mrays_1t", "3.5"}, {"mrays_mt", "6.25"},
      {"threads", "2"}, {"false_miss", "0"}, {"false_hit", "0"}, {"wrong_prim", "0"}, {"wrong_t", "0"},
      {"max_rel_t_err", "6.2e-06"}, {"mean_rel_t_err", "7.1e-08"}, {"embree_ratio_mt", "0.5"}};
  for (const auto& [key, value] : changes) {
    if (value.empty()) fields.erase(key);
    else fields[key] = value;
  }
  std::string text = "{";
  for (const auto& [key, value] : fields) text += (text.size() > 1 ? ", \"" : "\"") + key + "\": " + value;
  return text + "}";
}

/// A JSON array of the given rows.
std::string bench_array(const std::vector<std::string>& rows) {
  std::string text = "[\n";
  for (size_t i = 0; i < rows.size(); ++i) text += "  " + rows[i] + (i + 1 < rows.size() ? ",\n" : "\n");
  return text + "]\n";
}

BenchData parsed_bench(const std::vector<std::string>& rows) {
  auto parsed = parse_bench_json(bench_array(rows), "t.json");
  EXPECT_TRUE(parsed.ok()) << parsed.error().message;
  return parsed.ok() ? parsed.value() : BenchData{};
}

TEST(BenchChart, LoadsTheCheckedInFile) {
  // Made by accelviz-cli bench (tests/app/data/README.md says how): two groups, the first
  // with every structure, three kernels and Embree, the second with no wrong answer at all.
  auto loaded = load_bench_json(ACCEL_TEST_DATA_DIR "/bench_chart.json");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const BenchData& d = loaded.value();
  ASSERT_EQ(d.rows.size(), 23u);
  ASSERT_EQ(d.groups.size(), 2u);
  EXPECT_EQ(d.groups[0].label(), "bunny.obj, bunny_edges_20k.txt");
  EXPECT_EQ(d.groups[0].rows.size(), 17u);
  EXPECT_EQ(d.groups[1].label(), "procedural:cornell, random:2000:1");
  EXPECT_EQ(d.groups[1].rows.size(), 6u);
  EXPECT_EQ(d.groups[1].n_rays, 2000u);
  size_t embree = 0;
  for (const BenchRow& r : d.rows) {
    EXPECT_GT(r.mrays_mt, 0.0);
    if (r.is_embree()) {
      ++embree;
      EXPECT_FALSE(r.embree_ratio_mt.has_value());
    } else {
      EXPECT_TRUE(r.embree_ratio_mt.has_value()) << r.structure;
    }
    if (r.kernel == "watertight" || r.kernel == "double") {
      EXPECT_EQ(r.wrong_answers(), 0u) << r.structure;
    }
  }
  EXPECT_EQ(embree, 4u);

  const ChartModel m = make_chart(d, ChartOptions{});
  EXPECT_EQ(m.points.size(), 17u);
  EXPECT_EQ(m.kernels, (std::vector<std::string>{"watertight", "moller", "double", "embree"}));
  EXPECT_EQ(m.structures, (std::vector<std::string>{"grid", "octree", "kdtree", "bvh", "spheretree", "embree-medium",
                                                    "embree-high"}));
  ASSERT_TRUE(m.baseline_y.has_value());
}

TEST(BenchChart, BadFilesGiveOneLineNamingFileRowAndKey) {
  struct Case {
    std::string text;
    std::string expected;  // the whole message
  };
  const std::string good = bench_row();
  const Case cases[] = {
      {"", "t.json: not valid JSON: parse error at line 1, column 1: "},
      {"[{\"scene\": \n", "t.json: not valid JSON: parse error at line 2, column 1: "},
      {"{\"rows\": []}", "t.json: expected a JSON array of rows (accelviz-cli bench --out-json), got an object"},
      {"[]", "t.json: no rows (the array is empty)"},
      {"[" + good + ", 7]", "t.json: row 2: expected an object, got a number"},
      {bench_array({good, bench_row({{"mrays_mt", ""}})}), "t.json: row 2: missing key 'mrays_mt'"},
      {bench_array({bench_row({{"scene", ""}})}), "t.json: row 1: missing key 'scene'"},
      {bench_array({bench_row({{"n_rays", "\"2000\""}})}),
       "t.json: row 1: 'n_rays' must be a non-negative integer, got \"2000\""},
      {bench_array({bench_row({{"false_hit", "-1"}})}), "t.json: row 1: 'false_hit' must be a non-negative integer, got -1"},
      {bench_array({bench_row({{"threads", "2.5"}})}), "t.json: row 1: 'threads' must be a non-negative integer, got 2.5"},
      {bench_array({bench_row({{"n_rays", "0"}})}), "t.json: row 1: 'n_rays' must be at least 1, got 0"},
      {bench_array({bench_row({{"kernel", "3"}})}), "t.json: row 1: 'kernel' must be a string, got 3"},
      {bench_array({bench_row({{"build_ms", "-0.5"}})}), "t.json: row 1: 'build_ms' must be a non-negative number, got -0.5"},
      {bench_array({bench_row({{"mrays_1t", "null"}})}), "t.json: row 1: 'mrays_1t' must be a non-negative number, got null"},
      {bench_array({bench_row({{"embree_ratio_mt", "\"fast\""}})}),
       "t.json: row 1: 'embree_ratio_mt' must be a non-negative number or null, got \"fast\""},
  };
  for (const Case& c : cases) {
    auto parsed = parse_bench_json(c.text, "t.json");
    ASSERT_FALSE(parsed.ok()) << c.text;
    const std::string& message = parsed.error().message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    if (c.expected.ends_with(": ")) {
      EXPECT_TRUE(message.starts_with(c.expected)) << message;
    } else {
      EXPECT_EQ(message, c.expected);
    }
  }
  auto missing = load_bench_json("/nonexistent/bench.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message, "/nonexistent/bench.json: cannot read the file");

  // embree_ratio_mt may be null or absent (Embree rows, benches without Embree); unknown
  // keys are ignored.
  const BenchData d = parsed_bench({bench_row({{"embree_ratio_mt", "null"}}), bench_row({{"embree_ratio_mt", ""}}),
                                    bench_row({{"future_key", "[1, 2]"}, {"embree_ratio_1t", "0.25"}})});
  ASSERT_EQ(d.rows.size(), 3u);
  EXPECT_FALSE(d.rows[0].embree_ratio_mt.has_value());
  EXPECT_FALSE(d.rows[1].embree_ratio_mt.has_value());
  EXPECT_FALSE(d.rows[1].embree_ratio_1t.has_value());
  EXPECT_DOUBLE_EQ(d.rows[2].embree_ratio_mt.value(), 0.5);
  EXPECT_DOUBLE_EQ(d.rows[2].embree_ratio_1t.value(), 0.25);
  auto bad_1t = parse_bench_json(bench_array({bench_row({{"embree_ratio_1t", "true"}})}), "t.json");
  ASSERT_FALSE(bad_1t.ok());
  EXPECT_EQ(bad_1t.error().message, "t.json: row 1: 'embree_ratio_1t' must be a non-negative number or null, got true");
}

TEST(BenchChart, ErrorRateCountsWrongAnswersNotWrongT) {
  const BenchData d = parsed_bench(
      {bench_row({{"n_rays", "600"}, {"false_miss", "1"}, {"false_hit", "2"}, {"wrong_prim", "3"}, {"wrong_t", "4"}})});
  const BenchRow& r = d.rows[0];
  EXPECT_EQ(r.wrong_answers(), 6u);
  EXPECT_DOUBLE_EQ(r.error_rate(), 0.01);
  EXPECT_EQ(format_error_rate(650, 20000), "650 of 20,000 (3.25%)");
  EXPECT_EQ(format_error_rate(0, 2000), "0 of 2,000");
  EXPECT_EQ(format_error_rate(1, 1000000), "1 of 1,000,000 (0.0001%)");
}

TEST(BenchChart, LogAxisCoversWholeDecades) {
  const ChartAxis a = log_decade_axis(0.0054, 0.00915, true);
  EXPECT_TRUE(a.log);
  EXPECT_DOUBLE_EQ(a.lo, 1e-3);
  EXPECT_DOUBLE_EQ(a.hi, 1e-2);
  std::vector<std::string> labels;
  size_t minor = 0;
  for (const AxisTick& t : a.ticks) {
    if (t.major) labels.push_back(t.label);
    else ++minor;
  }
  EXPECT_EQ(labels, (std::vector<std::string>{"1e-3", "1e-2"}));
  EXPECT_EQ(minor, 8u);  // 2..9 x 1e-3
  EXPECT_NEAR(a.unit(2e-3), std::log10(2.0), 1e-6);
  EXPECT_NEAR(a.unit(std::sqrt(1e-5)), 0.5, 1e-6);
  EXPECT_EQ(a.ticks.front().exponent, -3);

  // An exact decade still gets one decade of room; exact powers stay in their decade.
  const ChartAxis one = log_decade_axis(1e-3, 1e-3, true);
  EXPECT_DOUBLE_EQ(one.lo, 1e-3);
  EXPECT_DOUBLE_EQ(one.hi, 1e-2);
  const ChartAxis two = log_decade_axis(1e-3, 1e-1, true);
  EXPECT_DOUBLE_EQ(two.lo, 1e-3);
  EXPECT_DOUBLE_EQ(two.hi, 1e-1);

  // Twelve decades: no minor ticks, every second decade labelled.
  const ChartAxis wide = log_decade_axis(3e-12, 0.5, true);
  EXPECT_EQ(wide.ticks.size(), 13u);
  size_t labelled = 0;
  for (const AxisTick& t : wide.ticks) {
    EXPECT_TRUE(t.major);
    labelled += t.labelled;
  }
  EXPECT_EQ(labelled, 7u);

  // Plain labels (the speed axis).
  std::vector<std::string> plain;
  for (const AxisTick& t : log_decade_axis(0.5, 40.0, false).ticks)
    if (t.major) plain.push_back(t.label);
  EXPECT_EQ(plain, (std::vector<std::string>{"0.1", "1", "10", "100"}));
}

TEST(BenchChart, LinearAxisUsesNiceSteps) {
  auto labels = [](const ChartAxis& a) {
    std::vector<std::string> out;
    for (const AxisTick& t : a.ticks) out.push_back(t.label);
    return out;
  };
  const ChartAxis a = linear_zero_axis(9.35);
  EXPECT_FALSE(a.log);
  EXPECT_DOUBLE_EQ(a.hi, 10.0);
  EXPECT_EQ(labels(a), (std::vector<std::string>{"0", "2", "4", "6", "8", "10"}));
  EXPECT_FLOAT_EQ(a.ticks[1].pos, 0.2f);
  EXPECT_EQ(labels(linear_zero_axis(2.6)), (std::vector<std::string>{"0", "0.5", "1", "1.5", "2", "2.5", "3"}));
  EXPECT_EQ(labels(linear_zero_axis(0.7)), (std::vector<std::string>{"0", "0.2", "0.4", "0.6", "0.8"}));
  EXPECT_EQ(labels(linear_zero_axis(130.0)), (std::vector<std::string>{"0", "25", "50", "75", "100", "125", "150"}));
  EXPECT_DOUBLE_EQ(linear_zero_axis(0.0).hi, 1.0);
  EXPECT_FLOAT_EQ(a.unit(5.0), 0.5f);
}

TEST(BenchChart, ZeroErrorRowsGoToTheBand) {
  // Two exact kernels (zero errors) and Moller with errors; Embree as the baseline.
  const BenchData d = parsed_bench({
      bench_row({{"structure", "\"grid\""}, {"mrays_mt", "2"}}),
      bench_row({{"structure", "\"bvh\""}, {"kernel", "\"double\""}, {"mrays_mt", "4"}}),
      bench_row({{"structure", "\"bvh\""}, {"mrays_mt", "5"}}),
      bench_row({{"structure", "\"bvh\""}, {"kernel", "\"moller\""}, {"false_miss", "2"}, {"mrays_mt", "6"}}),
      bench_row({{"structure", "\"embree-high\""}, {"kernel", "\"embree\""}, {"embree_ratio_mt", ""},
                 {"wrong_prim", "20"}, {"mrays_mt", "9.5"}}),
  });
  const ChartModel m = make_chart(d, ChartOptions{});
  ASSERT_EQ(m.points.size(), 5u);
  EXPECT_FLOAT_EQ(m.zero_band, ChartModel::kBandBase + 3 * ChartModel::kBandPerPoint);
  EXPECT_EQ(m.zero_label, "0 errors");
  // The x axis covers only the positive error rates: 2/2000 and 20/2000.
  EXPECT_DOUBLE_EQ(m.x.lo, 1e-3);
  EXPECT_DOUBLE_EQ(m.x.hi, 1e-2);
  EXPECT_EQ(m.x.ticks.front().note, "0.1%");
  // In the band, spread in legend order: watertight grid, watertight bvh, double bvh.
  const ChartPoint &grid = m.points[0], &bvh_double = m.points[1], &bvh = m.points[2];
  for (const ChartPoint* p : {&grid, &bvh_double, &bvh}) {
    EXPECT_TRUE(p->zero);
    EXPECT_GT(p->fx, 0.0f);
    EXPECT_LT(p->fx, m.zero_band);
  }
  EXPECT_LT(grid.fx, bvh.fx);
  EXPECT_LT(bvh.fx, bvh_double.fx);
  // Off the band: on the log axis, after the gap.
  const ChartPoint &moller = m.points[3], &embree = m.points[4];
  EXPECT_FALSE(moller.zero);
  EXPECT_DOUBLE_EQ(moller.x, 0.001);
  EXPECT_FLOAT_EQ(moller.fx, m.x_start());
  EXPECT_FLOAT_EQ(embree.fx, 1.0f);
  // y: 0..10 linear; the baseline is Embree's speed.
  EXPECT_DOUBLE_EQ(m.y.hi, 10.0);
  EXPECT_FLOAT_EQ(moller.fy, 0.6f);
  ASSERT_TRUE(m.baseline_y.has_value());
  EXPECT_DOUBLE_EQ(*m.baseline_y, 9.5);
  EXPECT_FLOAT_EQ(m.baseline_fy.value(), 0.95f);
  EXPECT_EQ(m.y_title, "Mrays/s, 2 threads");

  // No error anywhere: the band holds everything, and the axis still spans 1/n_rays.
  const BenchData exact = parsed_bench({bench_row(), bench_row({{"kernel", "\"double\""}})});
  const ChartModel e = make_chart(exact, ChartOptions{});
  EXPECT_TRUE(e.points[0].zero && e.points[1].zero);
  EXPECT_LE(e.x.lo, 1.0 / 2000.0);
  EXPECT_GE(e.x.hi, 1.0 / 2000.0);

  // t error as x: exact t goes to the band too.
  ChartOptions t_error;
  t_error.x = ChartX::MaxRelTErr;
  const ChartModel t = make_chart(parsed_bench({bench_row(), bench_row({{"max_rel_t_err", "0"}})}), t_error);
  EXPECT_FALSE(t.points[0].zero);
  EXPECT_TRUE(t.points[1].zero);
  EXPECT_EQ(t.zero_label, "exact t");
  EXPECT_DOUBLE_EQ(t.x.lo, 1e-6);
  EXPECT_TRUE(t.x.ticks.front().note.empty());
}

TEST(BenchChart, GroupsSpeedAndLogY) {
  const BenchData d = parsed_bench({
      bench_row({{"mrays_mt", "4"}, {"mrays_1t", "2"}}),
      bench_row({{"rays", "\"primary:64:64\""}, {"n_rays", "4096"}, {"mrays_mt", "40"}, {"threads", "8"}}),
      bench_row({{"structure", "\"grid\""}, {"mrays_mt", "0.5"}}),
      bench_row({{"scene", "\"../shared/scenes/bunny.obj\""}}),
  });
  ASSERT_EQ(d.groups.size(), 3u);
  EXPECT_EQ(d.groups[0].rows, (std::vector<size_t>{0, 2}));
  EXPECT_EQ(d.groups[1].rows, (std::vector<size_t>{1}));
  EXPECT_EQ(d.groups[1].n_rays, 4096u);
  EXPECT_EQ(d.groups[2].label(), "bunny.obj, random:2000:1");

  ChartOptions o;
  ChartModel m = make_chart(d, o);
  ASSERT_EQ(m.points.size(), 2u);
  EXPECT_EQ(m.points[0].row, 0u);
  EXPECT_EQ(m.points[1].row, 2u);
  EXPECT_DOUBLE_EQ(m.points[0].y, 4.0);
  EXPECT_FALSE(m.baseline_y.has_value());
  o.group = 1;
  m = make_chart(d, o);
  ASSERT_EQ(m.points.size(), 1u);
  EXPECT_EQ(m.points[0].row, 1u);
  EXPECT_EQ(m.y_title, "Mrays/s, 8 threads");
  o.group = 99;  // clamped to the last group
  EXPECT_EQ(make_chart(d, o).points[0].row, 3u);

  o.group = 0;
  o.speed = ChartSpeed::OneThread;
  m = make_chart(d, o);
  EXPECT_DOUBLE_EQ(m.points[0].y, 2.0);
  EXPECT_EQ(m.y_title, "Mrays/s, 1 thread");
  o.speed = ChartSpeed::AllThreads;
  o.log_y = true;
  m = make_chart(d, o);
  EXPECT_TRUE(m.y.log);
  EXPECT_DOUBLE_EQ(m.y.lo, 0.1);
  EXPECT_DOUBLE_EQ(m.y.hi, 10.0);
  EXPECT_NEAR(m.points[0].fy, std::log10(40.0) / 2.0, 1e-6);
  EXPECT_EQ(m.y_title, "Mrays/s, 2 threads (log scale)");
}

TEST(BenchChart, OptionsAndWindowState) {
  ChartOptions o;
  EXPECT_EQ(set_chart_option(o, "x=t-error"), "");
  EXPECT_EQ(o.x, ChartX::MaxRelTErr);
  EXPECT_EQ(set_chart_option(o, "speed=1t"), "");
  EXPECT_EQ(o.speed, ChartSpeed::OneThread);
  EXPECT_EQ(set_chart_option(o, "y=log"), "");
  EXPECT_TRUE(o.log_y);
  EXPECT_EQ(set_chart_option(o, "labels=off"), "");
  EXPECT_FALSE(o.labels);
  EXPECT_EQ(set_chart_option(o, "group=3"), "");
  EXPECT_EQ(o.group, 2u);
  EXPECT_EQ(set_chart_option(o, "speed=fast"), "speed: expected mt or 1t, got 'fast'");
  EXPECT_EQ(set_chart_option(o, "group=x"), "group: expected a group number from 1, got 'x'");

  BenchChartState state;
  auto error = load_bench_into(state, ACCEL_TEST_DATA_DIR "/bench_chart.json");
  ASSERT_FALSE(error.has_value()) << error->message;
  EXPECT_TRUE(state.open);
  ASSERT_TRUE(state.data.has_value());
  state.options.group = 1;
  // A failed load keeps what is shown and reports the error.
  error = load_bench_into(state, ACCEL_TEST_DATA_DIR "/bench_malformed.json");
  ASSERT_TRUE(error.has_value());
  EXPECT_TRUE(error->message.starts_with(ACCEL_TEST_DATA_DIR "/bench_malformed.json: not valid JSON: "));
  EXPECT_EQ(state.error, error->message);
  ASSERT_TRUE(state.data.has_value());
  EXPECT_EQ(state.data->rows.size(), 23u);
  EXPECT_EQ(state.options.group, 1u);
}

}  // namespace
}  // namespace viz
