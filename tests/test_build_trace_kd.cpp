// kd-tree construction recording (build_trace.h, #12), hand-checked on scenes of 2-4
// triangles: the exact steps of split=middle with round-robin axes (planes, counts, regions,
// leaf reasons), the SAH's candidate planes and costs (the split is their minimum, the empty-
// space bonus included), a no-gain leaf, and a straddling triangle counted in both children
// with clip=off but not with perfect splits. Every recorded build makes the normal build's tree.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "build_replay.h"
#include "scene.h"
#include "structures/kd_builder.h"

namespace accel {
namespace {

/// A triangle whose bounding box is [x, x+1] x [y, y+1] x [z, z+1]; `flip` = another
/// triangle with the same box.
void add_box_triangle(std::vector<Vec3>& p, std::vector<UVec3>& t, float x, float y, float z, bool flip = false) {
  const uint32_t i = uint32_t(p.size());
  if (!flip) {
    p.insert(p.end(), {Vec3(x, y, z), Vec3(x + 1, y, z), Vec3(x, y + 1, z + 1)});
  } else {
    p.insert(p.end(), {Vec3(x + 1, y + 1, z + 1), Vec3(x, y + 1, z), Vec3(x + 1, y, z + 1)});
  }
  t.push_back(UVec3(i, i + 1, i + 2));
}

const char* reason_name(LeafReason r) {
  switch (r) {
    case LeafReason::FewPrims: return "few";
    case LeafReason::MaxDepth: return "depth";
    case LeafReason::NoGain: return "nogain";
    case LeafReason::Cluster: return "cluster";
    case LeafReason::NoProgress: return "noprogress";
    case LeafReason::BadRefines: return "badrefines";
    case LeafReason::TooThin: return "thin";
  }
  return "?";
}

std::string list_of(const BuildTrace& trace, const BuildEvent& e) {
  std::ostringstream s;
  s << '{';
  for (uint32_t i = 0; i < e.list_count; ++i) s << (i ? " " : "") << trace.list(e)[i];
  s << '}';
  return s.str();
}

/// The steps in a compact form: "node 1<0 d1 {0}" = node 1, child of 0, depth 1, triangles
/// {0}; "split 0 x@2 1|2 both 0" = on x at 2, 1 triangle below, 2 above, 0 in both;
/// "cands 0 x 2" = 2 candidate planes on x.
std::string steps(const BuildTrace& trace) {
  static const char* const kAxis[] = {"x", "y", "z", "pca"};
  std::ostringstream out;
  for (const BuildEvent& e : trace.events) {
    if (out.tellp() > 0) out << ", ";
    switch (e.kind) {
      case BuildEventKind::SceneBox: out << "scene_box"; break;
      case BuildEventKind::Node:
        out << "node " << e.node << '<' << (e.parent == kNoBuildNode ? std::string("-") : std::to_string(e.parent))
            << " d" << e.depth << ' ' << list_of(trace, e);
        break;
      case BuildEventKind::Axis: out << "axis " << e.node << ' ' << kAxis[e.axis]; break;
      case BuildEventKind::Candidates: out << "cands " << e.node << ' ' << kAxis[e.axis] << ' ' << e.list_count; break;
      case BuildEventKind::Split:
        out << "split " << e.node << ' ' << kAxis[e.axis] << '@' << e.pos << ' ' << e.a << '|' << e.b << " both "
            << e.count;
        break;
      case BuildEventKind::Leaf: out << "leaf " << e.node << ' ' << reason_name(e.reason) << ' ' << list_of(trace, e); break;
      case BuildEventKind::Done: out << "done " << e.count; break;
      default: out << build_event_kind_name(e.kind); break;
    }
  }
  return out.str();
}

/// The first event of `kind` about `node`.
const BuildEvent* find(const BuildTrace& trace, BuildEventKind kind, uint32_t node) {
  for (const BuildEvent& e : trace.events)
    if (e.kind == kind && e.node == node) return &e;
  return nullptr;
}

void expect_box(const BuildTrace& trace, uint32_t node, const Aabb& want) {
  const BuildEvent* e = find(trace, BuildEventKind::Node, node);
  ASSERT_NE(e, nullptr) << "node " << node;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(e->box.min[k], want.min[k]) << "node " << node << " axis " << k;
    EXPECT_EQ(e->box.max[k], want.max[k]) << "node " << node << " axis " << k;
  }
}

Aabb box(Vec3 lo, Vec3 hi) {
  Aabb b;
  b.min = lo;
  b.max = hi;
  return b;
}

/// Builds normally and recorded: the same tree, bit for bit; returns the steps.
BuildTrace record(const Scene& scene, const KdBuildOptions& o) {
  auto normal = build_kd_tree(scene, o);
  BuildRecorder recorder;
  auto recorded = build_kd_tree(scene, o, nullptr, &recorder);
  EXPECT_TRUE(normal && recorded);
  if (!normal || !recorded) return {};
  const KdTreeData &a = normal.value(), &b = recorded.value();
  EXPECT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < std::min(a.nodes.size(), b.nodes.size()); ++i) {
    EXPECT_EQ(a.nodes[i].payload, b.nodes[i].payload) << "node " << i;
    EXPECT_EQ(a.nodes[i].bits, b.nodes[i].bits) << "node " << i;
  }
  EXPECT_EQ(a.prim_ids, b.prim_ids);
  BuildTrace trace = recorder.take();
  // The replay ends with the tree's leaves (their triangles) and inner nodes' planes.
  BuildReplay replay(trace);
  replay.seek(replay.steps());
  EXPECT_EQ(replay.nodes().size(), a.nodes.size());
  for (const ReplayNode& n : replay.nodes()) {
    if (n.id >= a.nodes.size()) continue;
    const KdNode& k = a.nodes[n.id];
    EXPECT_EQ(n.leaf, k.leaf()) << "node " << n.id;
    if (k.leaf()) {
      EXPECT_EQ(n.prims, std::vector<uint32_t>(a.prim_ids.begin() + k.prim_offset(),
                                               a.prim_ids.begin() + k.prim_offset() + k.prim_count()));
    } else {
      EXPECT_EQ(n.split_axis, k.axis()) << "node " << n.id;
      EXPECT_EQ(std::bit_cast<uint32_t>(n.split_pos), k.payload) << "node " << n.id;
    }
  }
  return trace;
}

/// Three unit-box triangles at x,y = (0,0), (3,0), (3,3), all in z [0,1].
Scene three_corners() {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  add_box_triangle(p, t, 0, 0, 0);
  add_box_triangle(p, t, 3, 0, 0);
  add_box_triangle(p, t, 3, 3, 0);
  return Scene(std::move(p), std::move(t), "three_corners");
}

TEST(KdBuildTrace, MiddleRoundRobinSteps) {
  // Root [0,4]x[0,4]x[0,1]: x at its middle 2 (triangle 0 below, 1 and 2 above); node 2
  // [2,4]x[0,4]: y (round robin, depth 1) at 2 (1 below, 2 above); one triangle per leaf.
  KdBuildOptions o;
  o.split = KdSplit::Middle;
  o.axis = KdAxis::RoundRobin;
  const BuildTrace trace = record(three_corners(), o);
  EXPECT_EQ(steps(trace),
            "scene_box, node 0<- d0 {0 1 2}, axis 0 x, split 0 x@2 1|2 both 0, "
            "node 1<0 d1 {0}, leaf 1 few {0}, "
            "node 2<0 d1 {1 2}, axis 2 y, split 2 y@2 1|1 both 0, "
            "node 3<2 d2 {1}, leaf 3 few {1}, node 4<2 d2 {2}, leaf 4 few {2}, done 5");
  ASSERT_EQ(trace.events.size(), 14u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(trace.events[0].box.min[k], 0.0f);
    EXPECT_EQ(trace.events[0].box.max[k], k == 2 ? 1.0f : 4.0f);
  }
  // The regions are the node views' (the parent's region cut at the plane).
  expect_box(trace, 0, box(Vec3(0, 0, 0), Vec3(4, 4, 1)));
  expect_box(trace, 1, box(Vec3(0, 0, 0), Vec3(2, 4, 1)));
  expect_box(trace, 2, box(Vec3(2, 0, 0), Vec3(4, 4, 1)));
  expect_box(trace, 3, box(Vec3(2, 0, 0), Vec3(4, 2, 1)));
  expect_box(trace, 4, box(Vec3(2, 2, 0), Vec3(4, 4, 1)));
  // Costs: root area 48, children 28 each: 1 + (28 * 1 + 28 * 2) / 48; the leaf would cost 3.
  const BuildEvent* s0 = find(trace, BuildEventKind::Split, 0);
  ASSERT_NE(s0, nullptr);
  EXPECT_NEAR(s0->cost, 2.75, 1e-6);
  EXPECT_FLOAT_EQ(s0->values[0], 3.0f);
  // Node 2: area 28, children 16: 1 + (16 + 16) / 28 (not below the leaf's 2: a bad refine, the first).
  const BuildEvent* s2 = find(trace, BuildEventKind::Split, 2);
  ASSERT_NE(s2, nullptr);
  EXPECT_NEAR(s2->cost, 1.0 + 32.0 / 28.0, 1e-6);
  EXPECT_FLOAT_EQ(s2->values[0], 2.0f);
}

TEST(KdBuildTrace, SahSplitIsTheCheapestCandidate) {
  // Two triangles filling [0,1]^3 and two filling [3,4]x[0,1]^2. Root (area 18, leaf cost 4):
  // on x the planes 1 and 3 cost 1 + (6 * 2 + 14 * 2) / 18 each (the first wins the tie); y
  // and z hold no plane inside. Node 1 = [0,1]^3: no plane inside at all, a no-gain leaf.
  // Node 2 = [1,4]x[0,1]^2 (area 14): the plane 3 cuts off empty space,
  // 0.8 * (1 + 6 * 2 / 14) < 2; its below child is empty, the above one no-gain.
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  add_box_triangle(p, t, 0, 0, 0);
  add_box_triangle(p, t, 0, 0, 0, true);
  add_box_triangle(p, t, 3, 0, 0);
  add_box_triangle(p, t, 3, 0, 0, true);
  const Scene scene(std::move(p), std::move(t), "two_pairs");
  KdBuildOptions o;  // sah, ct = ci = 1, empty_bonus 0.2
  const BuildTrace trace = record(scene, o);
  EXPECT_EQ(steps(trace),
            "scene_box, node 0<- d0 {0 1 2 3}, cands 0 x 2, cands 0 y 0, cands 0 z 0, split 0 x@1 2|2 both 0, "
            "node 1<0 d1 {0 1}, cands 1 x 0, cands 1 y 0, cands 1 z 0, leaf 1 nogain {0 1}, "
            "node 2<0 d1 {2 3}, cands 2 x 1, cands 2 y 0, cands 2 z 0, split 2 x@3 0|2 both 0, "
            "node 3<2 d2 {}, leaf 3 few {}, "
            "node 4<2 d2 {2 3}, cands 4 x 0, cands 4 y 0, cands 4 z 0, leaf 4 nogain {2 3}, done 5");

  const BuildEvent* c0 = find(trace, BuildEventKind::Candidates, 0);
  ASSERT_NE(c0, nullptr);
  ASSERT_EQ(c0->list_count, 2u);
  const SplitCandidate* c = trace.candidates_of(*c0);
  EXPECT_EQ(c[0].pos, 1.0f);
  EXPECT_EQ(c[1].pos, 3.0f);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(c[i].cost, 1.0 + 40.0 / 18.0, 1e-5);
    EXPECT_EQ(c[i].left, 2u);
    EXPECT_EQ(c[i].right, 2u);
  }
  const BuildEvent* c2 = find(trace, BuildEventKind::Candidates, 2);
  ASSERT_NE(c2, nullptr);
  ASSERT_EQ(c2->list_count, 1u);
  EXPECT_EQ(trace.candidates_of(*c2)[0].pos, 3.0f);
  EXPECT_NEAR(trace.candidates_of(*c2)[0].cost, 0.8 * (1.0 + 12.0 / 14.0), 1e-5);  // empty-space bonus
  EXPECT_EQ(trace.candidates_of(*c2)[0].left, 0u);
  EXPECT_EQ(trace.candidates_of(*c2)[0].right, 2u);
  expect_box(trace, 2, box(Vec3(1, 0, 0), Vec3(4, 1, 1)));
  expect_box(trace, 3, box(Vec3(1, 0, 0), Vec3(3, 1, 1)));
  expect_box(trace, 4, box(Vec3(3, 0, 0), Vec3(4, 1, 1)));

  // Every split: the first cheapest of its node's candidates (sweep order), at its cost,
  // below the leaf cost ci * N, with its counts (nothing straddles here).
  for (const BuildEvent& s : trace.events) {
    if (s.kind != BuildEventKind::Split) continue;
    const SplitCandidate* best = nullptr;
    int best_axis = -1;
    for (const BuildEvent& e : trace.events) {
      if (e.kind != BuildEventKind::Candidates || e.node != s.node) continue;
      for (uint32_t i = 0; i < e.list_count; ++i) {
        const SplitCandidate& k = trace.candidates_of(e)[i];
        if (!best || k.cost < best->cost) best = &k, best_axis = e.axis;
      }
    }
    ASSERT_NE(best, nullptr) << "node " << s.node;
    EXPECT_EQ(s.axis, best_axis) << "node " << s.node;
    EXPECT_EQ(s.pos, best->pos) << "node " << s.node;
    EXPECT_EQ(s.cost, best->cost) << "node " << s.node;
    EXPECT_LT(s.cost, s.values[0]) << "node " << s.node;
    EXPECT_EQ(s.a, best->left) << "node " << s.node;
    EXPECT_EQ(s.b, best->right) << "node " << s.node;
  }
  EXPECT_FLOAT_EQ(find(trace, BuildEventKind::Split, 0)->values[0], 4.0f);
  EXPECT_FLOAT_EQ(find(trace, BuildEventKind::Split, 2)->values[0], 2.0f);
}

TEST(KdBuildTrace, SahNoGainLeaf) {
  // [0,1]^3 and [3,4]x[0,2]x[0,1] (root area 28, leaf cost 2): x at 1 or 3 costs
  // 1 + (10 + 22) / 28, y at 1 costs 1 + (18 * 2 + 18 * 1) / 28, z has no plane inside.
  // None is below 2: the root stays a leaf.
  std::vector<Vec3> p = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 1), Vec3(3, 0, 0), Vec3(4, 0, 0), Vec3(3, 2, 1)};
  std::vector<UVec3> t = {UVec3(0, 1, 2), UVec3(3, 4, 5)};
  const Scene scene(std::move(p), std::move(t), "no_gain");
  const BuildTrace trace = record(scene, KdBuildOptions{});
  EXPECT_EQ(steps(trace), "scene_box, node 0<- d0 {0 1}, cands 0 x 2, cands 0 y 1, cands 0 z 0, leaf 0 nogain {0 1}, done 1");
  const BuildEvent* cx = find(trace, BuildEventKind::Candidates, 0);
  ASSERT_NE(cx, nullptr);
  ASSERT_EQ(cx->list_count, 2u);
  for (int i = 0; i < 2; ++i) {
    const SplitCandidate& k = trace.candidates_of(*cx)[i];
    EXPECT_EQ(k.pos, i == 0 ? 1.0f : 3.0f);
    EXPECT_NEAR(k.cost, 1.0 + 32.0 / 28.0, 1e-5);
    EXPECT_EQ(k.left, 1u);
    EXPECT_EQ(k.right, 1u);
  }
  const BuildEvent& cy = *(cx + 1);
  ASSERT_EQ(cy.kind, BuildEventKind::Candidates);
  ASSERT_EQ(cy.list_count, 1u);
  EXPECT_EQ(trace.candidates_of(cy)[0].pos, 1.0f);
  EXPECT_NEAR(trace.candidates_of(cy)[0].cost, 1.0 + 54.0 / 28.0, 1e-5);
  EXPECT_EQ(trace.candidates_of(cy)[0].left, 2u);
  EXPECT_EQ(trace.candidates_of(cy)[0].right, 1u);
}

TEST(KdBuildTrace, StraddlerInBothChildrenOnlyWithoutClipping) {
  // In z = 0: triangle 0 = (1,4) (4,0) (4,4), box [1,4]x[0,4]; triangle 1 in [0,1]^2. The root
  // [0,4]^2 is split on x at 2: triangle 0 crosses it, in both children. In the below child
  // [0,2]x[0,4] its part has y in [8/3, 4], so the split on y at 2 puts it above only with
  // perfect splits; clip=off keeps its box [1,2]x[0,4] there, in both, and the below
  // grandchild [0,2]^2 gets both triangles: its split on x at 1 would be the path's third
  // whose cost is not below the leaf's (2.5, 2.5, 2 vs 2), a bad-refine leaf (BadRefines).
  std::vector<Vec3> p = {Vec3(1, 4, 0), Vec3(4, 0, 0), Vec3(4, 4, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  std::vector<UVec3> t = {UVec3(0, 1, 2), UVec3(3, 4, 5)};
  const Scene scene(std::move(p), std::move(t), "straddler");
  KdBuildOptions o;
  o.split = KdSplit::Middle;
  o.axis = KdAxis::RoundRobin;
  o.clip = true;
  const BuildTrace on = record(scene, o);
  EXPECT_EQ(steps(on),
            "scene_box, node 0<- d0 {0 1}, axis 0 x, split 0 x@2 2|1 both 1, "
            "node 1<0 d1 {0 1}, axis 1 y, split 1 y@2 1|1 both 0, "
            "node 2<1 d2 {1}, leaf 2 few {1}, node 3<1 d2 {0}, leaf 3 few {0}, "
            "node 4<0 d1 {0}, leaf 4 few {0}, done 5");
  expect_box(on, 3, box(Vec3(0, 2, 0), Vec3(2, 4, 0)));
  expect_box(on, 4, box(Vec3(2, 0, 0), Vec3(4, 4, 0)));
  o.clip = false;
  const BuildTrace off = record(scene, o);
  EXPECT_EQ(steps(off),
            "scene_box, node 0<- d0 {0 1}, axis 0 x, split 0 x@2 2|1 both 1, "
            "node 1<0 d1 {0 1}, axis 1 y, split 1 y@2 2|1 both 1, "
            "node 2<1 d2 {0 1}, axis 2 x, leaf 2 badrefines {0 1}, node 3<1 d2 {0}, leaf 3 few {0}, "
            "node 4<0 d1 {0}, leaf 4 few {0}, done 5");
  expect_box(off, 2, box(Vec3(0, 0, 0), Vec3(2, 2, 0)));
}

TEST(KdBuildTrace, DepthLimitAndLeafSize) {
  // max_depth 1: the root's children are depth-limit leaves; leaf_size 3: the root is a leaf.
  KdBuildOptions o;
  o.split = KdSplit::Middle;
  o.axis = KdAxis::Longest;
  o.max_depth = 1;
  EXPECT_EQ(steps(record(three_corners(), o)),
            "scene_box, node 0<- d0 {0 1 2}, axis 0 x, split 0 x@2 1|2 both 0, "
            "node 1<0 d1 {0}, leaf 1 few {0}, node 2<0 d1 {1 2}, leaf 2 depth {1 2}, done 3");
  o.leaf_size = 3;
  EXPECT_EQ(steps(record(three_corners(), o)), "scene_box, node 0<- d0 {0 1 2}, leaf 0 few {0 1 2}, done 1");
}

TEST(KdBuildTrace, DepthLimitedRecordingOfALargerSceneKeepsTheTree) {
  // 600 triangles on a diagonal, recorded to depth 2: the same tree, nodes below depth 3
  // neither listed nor announced.
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (int i = 0; i < 600; ++i) add_box_triangle(p, t, 0.01f * float(i), 0.013f * float(i % 37), 0.02f * float(i % 11));
  const Scene scene(std::move(p), std::move(t), "diagonal");
  for (KdSplit split : {KdSplit::Sah, KdSplit::Middle, KdSplit::Median}) {
    KdBuildOptions o;
    o.split = split;
    auto normal = build_kd_tree(scene, o);
    BuildRecorder recorder(2);
    auto recorded = build_kd_tree(scene, o, nullptr, &recorder);
    ASSERT_TRUE(normal && recorded);
    ASSERT_EQ(normal.value().nodes.size(), recorded.value().nodes.size());
    for (size_t i = 0; i < normal.value().nodes.size(); ++i)
      ASSERT_EQ(normal.value().nodes[i].bits, recorded.value().nodes[i].bits);
    EXPECT_EQ(normal.value().prim_ids, recorded.value().prim_ids);
    const BuildTrace& trace = recorder.trace();
    EXPECT_EQ(trace.events.back().kind, BuildEventKind::Done);
    EXPECT_EQ(trace.events.back().count, normal.value().nodes.size());
    for (const BuildEvent& e : trace.events) {
      if (e.kind == BuildEventKind::Node) {
        EXPECT_LE(e.depth, 2);
      }
      if (e.kind == BuildEventKind::Unrecorded) {
        EXPECT_EQ(e.depth, 3);
      }
    }
  }
}

TEST(KdBuildTrace, TiedEventsKeepTheTreeWhateverTheRootsSort) {
  // A normal build sorts the root's lists by radix where no -0 can make the order of tied
  // events show, a recorded one with std::sort: the same tree on a grid whose triangles share
  // every coordinate (floor triangles flat in z, walls flat in x), and on the same grid with
  // -0 among them, where the normal build takes std::sort as well.
  for (const float zero : {0.0f, -0.0f}) {
    std::vector<Vec3> p;
    std::vector<UVec3> t;
    const auto tri = [&](Vec3 a, Vec3 b, Vec3 c) {
      const uint32_t i = uint32_t(p.size());
      p.insert(p.end(), {a, b, c});
      t.push_back(UVec3(i, i + 1, i + 2));
    };
    for (int i = 0; i < 12; ++i) {
      for (int j = 0; j < 12; ++j) {
        const float x = i == 0 ? zero : float(i), y = j == 0 ? zero : float(j);
        tri(Vec3(x, y, zero), Vec3(x + 1, y, zero), Vec3(x, y + 1, zero));
        tri(Vec3(x + 1, y, zero), Vec3(x + 1, y + 1, zero), Vec3(x, y + 1, zero));
        if ((i + j) % 3 == 0) tri(Vec3(x, y, zero), Vec3(x, y + 1, 1.0f), Vec3(x, y + 2, 2.0f));
      }
    }
    // Large triangles on integer coordinates, crossing each other's planes: thousands of
    // re-clipped straddlers, whose events are merged into the lists the root's sort ordered.
    std::mt19937 rng(5);
    for (int i = 0; i < 3000; ++i) {
      const Vec3 a(float(rng() % 20), float(rng() % 20), float(rng() % 20));
      tri(a, a + Vec3(float(rng() % 10), float(rng() % 10), 0.0f), a + Vec3(0.0f, float(rng() % 10), 9.0f));
    }
    const Scene scene(std::move(p), std::move(t), "grid");
    for (bool clip : {true, false}) {
      KdBuildOptions o;
      o.clip = clip;
      o.leaf_size = 2;
      SCOPED_TRACE(std::string(std::signbit(zero) ? "-0" : "+0") + (clip ? " clip on" : " clip off"));
      record(scene, o);  // checks the two trees bit for bit
    }
  }
}

}  // namespace
}  // namespace accel
