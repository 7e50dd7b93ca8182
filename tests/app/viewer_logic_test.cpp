// The viewer's interaction logic without a window: the script parser, the camera model
// behind picking, the pseudo-code mapping of real traces, structure -> instances, the debug
// ray's replay after a rebuild, and the compare / sweep work. (TracePlayer itself is tested
// in tests/test_trace_player.cpp.)
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <set>

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

}  // namespace
}  // namespace viz
