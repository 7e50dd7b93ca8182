// Construction recording (build_trace.h, build_replay.h), for every structure and builder
// option: the recorded build makes exactly the structure of the normal build, and replaying
// its steps reconstructs that structure -- nodes, bounds and triangle lists.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "build_replay.h"
#include "random.h"
#include "registry.h"
#include "scene.h"
#include "structures/bvh_builders.h"

namespace accel {
namespace {

/// 300 overlapping random triangles in the unit cube (a small soup: every builder, every split kind).
Scene small_soup() {
  std::vector<Vec3> positions;
  std::vector<UVec3> triangles;
  Rng rng(7);
  for (uint32_t i = 0; i < 300; ++i) {
    const Vec3 c(rng.uniform(), rng.uniform(), rng.uniform());
    for (int k = 0; k < 3; ++k)
      positions.push_back(c + Vec3(rng.uniform(-0.08f, 0.08f), rng.uniform(-0.08f, 0.08f), rng.uniform(-0.08f, 0.08f)));
    triangles.push_back(UVec3(3 * i, 3 * i + 1, 3 * i + 2));
  }
  return Scene(std::move(positions), std::move(triangles), "small_soup");
}

const Scene& soup() {
  static const Scene s = small_soup();
  return s;
}
const Scene& cornell() {
  static const Scene s = make_procedural_scene("cornell").value();
  return s;
}

/// A node as both sides see it, comparable bit for bit (-0 and +0 differ, NaN equals itself).
struct NodeHead {  // 4-byte fields only: no padding, so memcmp compares the values
  int32_t depth = 0;  ///< grid: the cell's linear index
  int32_t leaf = 0;
  float box[6] = {};
  float sphere[4] = {};
  int32_t split_axis = -1;
  float split_pos = 0.0f;
};
struct NodeKey {
  NodeHead head;
  std::vector<uint32_t> prims;
  bool operator<(const NodeKey& o) const {
    const int c = std::memcmp(&head, &o.head, sizeof(NodeHead));
    return c < 0 || (c == 0 && prims < o.prims);
  }
  bool operator==(const NodeKey& o) const {
    return std::memcmp(&head, &o.head, sizeof(NodeHead)) == 0 && prims == o.prims;
  }
};

std::string describe(const NodeKey& k) {
  std::ostringstream s;
  const NodeHead& h = k.head;
  s << (h.leaf ? "leaf" : "inner") << " depth " << h.depth << " box [" << h.box[0] << ' ' << h.box[1] << ' '
    << h.box[2] << " | " << h.box[3] << ' ' << h.box[4] << ' ' << h.box[5] << "] sphere r " << h.sphere[3]
    << " split " << h.split_axis << '@' << h.split_pos << " prims " << k.prims.size();
  return s.str();
}

void set_box(NodeHead& h, const Aabb& b) {
  const float v[6] = {b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z};
  std::copy(v, v + 6, h.box);
}
void set_sphere(NodeHead& h, const BoundingSphere& s) {
  const float v[4] = {s.center.x, s.center.y, s.center.z, s.radius};
  std::copy(v, v + 4, h.sphere);
}

/// What the structure holds: every node (the grid: every non-empty cell, by its index).
std::vector<NodeKey> structure_nodes(const Structure& s, const std::string& name) {
  std::vector<NodeKey> keys;
  s.for_each_node([&](const NodeView& v) {
    NodeKey k;
    k.head.leaf = v.leaf;
    if (name == "grid") {
      k.head.depth = int(v.id);  // a cell: its linear index and its triangles
      k.prims = s.node_prims(v.id);
      if (!k.prims.empty()) keys.push_back(k);
      return;
    }
    k.head.depth = v.depth;
    set_box(k.head, v.box);
    if (name == "spheretree") set_sphere(k.head, v.sphere);
    if (name == "kdtree" && !v.leaf) {
      k.head.split_axis = v.split_axis;
      k.head.split_pos = v.split_pos;
    }
    if (v.leaf) k.prims = s.node_prims(v.id);
    keys.push_back(k);
  });
  std::sort(keys.begin(), keys.end());
  return keys;
}

/// What the replay of every recorded step holds, in the same terms.
std::vector<NodeKey> replayed_nodes(const BuildReplay& replay, const std::string& name) {
  std::vector<NodeKey> keys;
  if (name == "grid") {
    const ReplayGrid& g = replay.grid();
    for (size_t c = 0; c < g.cells.size(); ++c) {
      if (g.cells[c].empty()) continue;
      NodeKey k;
      k.head.leaf = true;
      k.head.depth = int(c);
      k.prims = g.cells[c];
      keys.push_back(k);
    }
    std::sort(keys.begin(), keys.end());
    return keys;
  }
  const std::vector<int> depth = replay.depths();
  for (size_t i = 0; i < replay.nodes().size(); ++i) {
    const ReplayNode& n = replay.nodes()[i];
    if (n.gone) continue;
    NodeKey k;
    k.head.leaf = n.leaf;
    k.head.depth = depth[i];
    set_box(k.head, n.box);
    if (name == "spheretree") set_sphere(k.head, n.sphere);
    if (name == "kdtree" && !n.leaf) {
      k.head.split_axis = n.split_axis;
      k.head.split_pos = n.split_pos;
    }
    if (n.leaf) k.prims = n.prims;
    keys.push_back(k);
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

void expect_same_nodes(const std::vector<NodeKey>& want, const std::vector<NodeKey>& got, const std::string& what) {
  ASSERT_EQ(want.size(), got.size()) << what << ": node count";
  for (size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(want[i] == got[i]) << what << ": node " << i << " of " << want.size() << "\n  want " << describe(want[i])
                                   << "\n  got  " << describe(got[i]);
}

struct Config {
  std::string structure;
  std::vector<std::string> params;
};

std::string config_name(const Config& c) {
  std::string s = c.structure;
  for (const std::string& p : c.params) s += " " + p;
  return s;
}

std::vector<Config> all_configs() {
  std::vector<Config> c = {
      {"brute", {}},
      {"grid", {}},
      {"grid", {"insert=bbox"}},
      {"grid", {"resolution=avgsize", "lambda=1"}},
      {"grid", {"res=5,3,4", "insert=exact"}},
      {"octree", {}},
      {"octree", {"insert=bbox"}},
      {"octree", {"max_prims=2", "max_depth=4"}},
      {"kdtree", {}},
      {"kdtree", {"clip=off"}},
      {"kdtree", {"split=middle"}},
      {"kdtree", {"split=median", "axis=round_robin"}},
      {"kdtree", {"split=middle", "axis=round_robin", "leaf_size=3"}},
  };
  for (const char* s : {"bvh", "spheretree"}) {
    for (const BvhBuilderInfo& row : bvh_builder_table()) {
      if (row.splits_triangles) continue;  // below, with duplicate references at every node
      const char* b = row.name;
      c.push_back({s, {std::string("builder=") + b}});
      if (std::string(s) == "bvh") c.push_back({s, {std::string("builder=") + b, "width=2"}});
    }
    c.push_back({s, {"builder=median", "axis=x", "leaf_size=1"}});
    c.push_back({s, {"builder=median", "axis=round_robin"}});
    c.push_back({s, {"builder=binned_sah", "bins=4", "leaf_size=2"}});
    // Spatial splits (duplicate references), at every node the object split overlaps.
    c.push_back({s, {"builder=sbvh", "sbvh_alpha=0"}});
    if (std::string(s) == "bvh") c.push_back({s, {"builder=sbvh", "width=2", "bins=4", "leaf_size=2"}});
  }
  c.push_back({"bvh", {"width=4"}});  // the default is 8 wide: the 4-wide collapse too
  c.push_back({"bvh", {"width=4", "builder=bottom_up"}});
  return c;
}

class RecordedBuild : public ::testing::TestWithParam<std::tuple<Config, int>> {};

TEST_P(RecordedBuild, MakesTheSameStructureAndReplaysToIt) {
  const Config& config = std::get<0>(GetParam());
  const Scene& scene = std::get<1>(GetParam()) == 0 ? soup() : cornell();
  auto normal = build_structure(config.structure, scene, config.params);
  ASSERT_TRUE(normal) << normal.error().message;
  BuildRecorder recorder;
  auto recorded = build_structure(config.structure, scene, config.params, Kernel::Watertight, nullptr, &recorder);
  ASSERT_TRUE(recorded) << recorded.error().message;

  const std::vector<NodeKey> want = structure_nodes(*normal.value(), config.structure);
  expect_same_nodes(want, structure_nodes(*recorded.value(), config.structure), "recorded build vs normal build");

  const BuildTrace& trace = recorder.trace();
  EXPECT_EQ(trace.coverage(), "complete");
  ASSERT_FALSE(trace.events.empty());
  EXPECT_EQ(trace.events.front().kind, BuildEventKind::SceneBox);
  EXPECT_EQ(trace.events.back().kind, BuildEventKind::Done);
  BuildReplay replay(trace);
  replay.seek(replay.steps());
  expect_same_nodes(want, replayed_nodes(replay, config.structure), "replay of the recorded steps");

  // Going back and forth lands on the same state.
  replay.seek(replay.steps() / 2);
  replay.seek(replay.steps());
  expect_same_nodes(want, replayed_nodes(replay, config.structure), "replay after seeking back");
  for (const BuildEvent& e : trace.events) EXPECT_FALSE(describe_build_event(trace, e).empty());
}

INSTANTIATE_TEST_SUITE_P(AllStructures, RecordedBuild,
                         ::testing::Combine(::testing::ValuesIn(all_configs()), ::testing::Values(0, 1)),
                         [](const ::testing::TestParamInfo<std::tuple<Config, int>>& param_info) {
                           std::string n = config_name(std::get<0>(param_info.param)) +
                                           (std::get<1>(param_info.param) == 0 ? "_soup" : "_cornell");
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

const Scene& big_soup() {
  static const Scene s = make_procedural_scene("soup").value();
  return s;
}

// The recorded build runs serially; the normal one takes the parallel paths on 10k triangles.
TEST(BuildRecorder, RecordedBuildOfALargerSceneEqualsTheParallelBuild) {
  for (const char* name : {"grid", "octree", "kdtree", "bvh", "spheretree"}) {
    auto normal = build_structure(name, big_soup(), {});
    ASSERT_TRUE(normal) << name;
    BuildRecorder recorder;
    auto recorded = build_structure(name, big_soup(), {}, Kernel::Watertight, nullptr, &recorder);
    ASSERT_TRUE(recorded) << name;
    expect_same_nodes(structure_nodes(*normal.value(), name), structure_nodes(*recorded.value(), name), name);
  }
}

// 300 identical triangles: insertion grows a chain deeper than the depth bound, which is
// rebuilt balanced (limit_depth in bvh_builders.cpp): recorded as clusters, merges and a
// Replace step, so the replay still reconstructs the tree.
TEST(BuildRecorder, DepthBoundRebuildIsReplayed) {
  std::vector<Vec3> positions;
  std::vector<UVec3> triangles;
  for (uint32_t i = 0; i < 300; ++i) {
    positions.insert(positions.end(), {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
    triangles.push_back(UVec3(3 * i, 3 * i + 1, 3 * i + 2));
  }
  const Scene same(std::move(positions), std::move(triangles), "identical");
  for (const BvhBuilderInfo& row : bvh_builder_table()) {
    if (row.top_down) continue;  // the bottom-up builders rebuild past the bound
    const char* builder = row.name;
    for (const char* width : {"width=2", "width=4"}) {
      const std::vector<std::string> params = {std::string("builder=") + builder, width};
      auto normal = build_structure("bvh", same, params);
      ASSERT_TRUE(normal);
      BuildRecorder recorder;
      auto recorded = build_structure("bvh", same, params, Kernel::Watertight, nullptr, &recorder);
      ASSERT_TRUE(recorded);
      const std::vector<NodeKey> want = structure_nodes(*normal.value(), "bvh");
      expect_same_nodes(want, structure_nodes(*recorded.value(), "bvh"), builder);
      BuildReplay replay(recorder.trace());
      replay.seek(replay.steps());
      expect_same_nodes(want, replayed_nodes(replay, "bvh"), std::string(builder) + " replay");
    }
  }
}

TEST(BuildRecorder, DepthLimitRecordsTheTopLevelsOnly) {
  auto normal = build_structure("bvh", big_soup(), {"width=2"});
  ASSERT_TRUE(normal);
  BuildRecorder recorder(3);
  auto recorded = build_structure("bvh", big_soup(), {"width=2"}, Kernel::Watertight, nullptr, &recorder);
  ASSERT_TRUE(recorded);
  expect_same_nodes(structure_nodes(*normal.value(), "bvh"), structure_nodes(*recorded.value(), "bvh"), "bvh");
  const BuildTrace& trace = recorder.trace();
  const int deepest = int(normal.value()->build_stats().max_depth);
  EXPECT_EQ(trace.max_depth_seen, deepest);
  EXPECT_EQ(trace.coverage(), "recorded to depth 3 of " + std::to_string(deepest));
  size_t unrecorded = 0;
  for (const BuildEvent& e : trace.events) {
    if (e.kind == BuildEventKind::Node) {
      EXPECT_LE(e.depth, 3);
    }
    if (e.kind == BuildEventKind::Unrecorded) {
      EXPECT_EQ(e.depth, 4);
      ++unrecorded;
    }
  }
  EXPECT_EQ(unrecorded, 16u);  // the binary tree's 16 nodes at depth 4 (no leaf above it on 10k triangles)
  BuildReplay replay(trace);
  replay.seek(replay.steps());
  EXPECT_EQ(replay.live_nodes(), 1u + 2 + 4 + 8 + 16);
}

TEST(BuildRecorder, BudgetHalvesTheDepthUntilTheStepsFit) {
  const StructureInfo& info = *find_structure("bvh").value();
  const ParamSet params = ParamSet::parse(info.params, {}, "bvh").value();
  const size_t budget = size_t(2) << 20;
  auto recorded = build_structure_recorded(info, big_soup(), params, Kernel::Watertight, budget);
  ASSERT_TRUE(recorded);
  const BuildTrace& trace = recorded.value().trace;
  EXPECT_FALSE(trace.truncated);
  EXPECT_LE(trace.bytes(), budget);
  EXPECT_LT(trace.depth_limit, trace.max_depth_seen);
  EXPECT_NE(trace.coverage().find("recorded to depth"), std::string::npos) << trace.coverage();
  auto normal = build_structure("bvh", big_soup(), {});
  expect_same_nodes(structure_nodes(*normal.value(), "bvh"), structure_nodes(*recorded.value().structure, "bvh"),
                    "bvh");
}

TEST(BuildRecorder, StopsAtTheBudgetWithoutAStall) {
  BuildRecorder recorder(std::numeric_limits<int>::max(), 64 << 10);
  auto recorded = build_structure("bvh", big_soup(), {}, Kernel::Watertight, nullptr, &recorder);
  ASSERT_TRUE(recorded);  // the build itself completes
  EXPECT_TRUE(recorder.trace().truncated);
  EXPECT_LE(recorder.trace().bytes(), size_t(64) << 10);
  EXPECT_NE(recorder.trace().coverage().find("stopped at the step budget"), std::string::npos);
}

// The counter "SAH cost so far": the root alone costs ci * N, the finished tree what the
// structure's statistics say.
TEST(BuildReplay, SahCostSoFarEndsAtTheTreesCost) {
  for (const BvhBuilderInfo& row : bvh_builder_table()) {
    const char* builder = row.name;
    BuildRecorder recorder;
    auto built = build_structure("bvh", cornell(), {std::string("builder=") + builder, "width=2", "ct=1", "ci=2"},
                                 Kernel::Watertight, nullptr, &recorder);
    ASSERT_TRUE(built);
    BuildReplay replay(recorder.trace());
    if (row.top_down) {
      replay.seek(2);  // scene box, root node
      EXPECT_DOUBLE_EQ(replay.sah_cost(1.0, 2.0), 2.0 * double(cornell().valid_prims().size()));
    }
    replay.seek(replay.steps());
    EXPECT_NEAR(replay.sah_cost(1.0, 2.0), built.value()->build_stats().sah_cost, 1e-6 * replay.sah_cost(1.0, 2.0))
        << builder;
  }
  // The wide layouts: after the collapse steps, the collapsed tree's cost, whose leaves are
  // priced per test of four triangles.
  for (const char* width : {"4", "8"}) {
    BuildRecorder recorder;
    auto built = build_structure("bvh", cornell(), {std::string("width=") + width, "ct=1", "ci=2"}, Kernel::Watertight,
                                 nullptr, &recorder);
    ASSERT_TRUE(built);
    const BuildStats stats = built.value()->build_stats();
    EXPECT_EQ(stats.sah_prims_per_test, 4);
    BuildReplay replay(recorder.trace());
    replay.seek(replay.steps());
    EXPECT_NEAR(replay.sah_cost(1.0, 2.0, stats.sah_prims_per_test), stats.sah_cost, 1e-6 * stats.sah_cost)
        << "width " << width;
  }
}

TEST(BuildTraceJson, OneLinePerStepAfterAHeader) {
  BuildRecorder recorder;
  ASSERT_TRUE(build_structure("bvh", cornell(), {}, Kernel::Watertight, nullptr, &recorder));
  std::ostringstream out;
  write_build_trace_jsonl(recorder.trace(), out);
  const std::string text = out.str();
  EXPECT_EQ(size_t(std::count(text.begin(), text.end(), '\n')), recorder.trace().events.size() + 1);
  EXPECT_EQ(text.rfind("{\"steps\":" + std::to_string(recorder.trace().events.size()), 0), 0u);
  EXPECT_NE(text.find("\"kind\":\"candidates\""), std::string::npos);
  EXPECT_NE(text.find("\"kind\":\"collapse\""), std::string::npos);
}

// The viewer's first recording of a huge scene stops at half a balanced tree's depth, so it
// is not recorded in full only to be recorded again; smaller scenes record every depth.
TEST(RecordingFirstDepthLimit, HalfTheBalancedDepthAboveTheLargeSceneSize) {
  EXPECT_EQ(recording_first_depth_limit(0), std::numeric_limits<int>::max());
  EXPECT_EQ(recording_first_depth_limit(kLargeRecordingTriangles), std::numeric_limits<int>::max());
  EXPECT_EQ(recording_first_depth_limit(kLargeRecordingTriangles + 1), 9);  // ceil(log2 200001) = 18
  EXPECT_EQ(recording_first_depth_limit(size_t(1) << 20), 10);
  EXPECT_EQ(recording_first_depth_limit(size_t(10'000'000)), 12);  // ceil(log2 1e7) = 24
}

}  // namespace
}  // namespace accel
