// The spatial-split builder (builder=sbvh, bvh_spatial_builder.h): it splits where object
// splits cannot separate the triangles, its clipped boxes are conservative, its trees keep
// build_bvh_tree()'s guarantees (with duplicate references), answer exactly as brute force,
// respect the reference budget and do not depend on the thread count.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "batch.h"
#include "build_replay.h"
#include "build_trace.h"
#include "random.h"
#include "ray_gen.h"
#include "registry.h"
#include "scene.h"
#include "structures/bvh_builders.h"
#include "structures/bvh_spatial_builder.h"
#include "build_tree_compare.h"
#include "test_support.h"
#include "trace.h"

namespace accel {
namespace {

using testing::expect_same_tree;
using testing::expect_valid_tree_shape;

/// Long thin slivers along the diagonals of the unit square (every one's box is nearly the
/// whole scene, so no object split separates them) among small triangles scattered in the
/// cube: the case spatial splits are for.
Scene crossing_slivers() {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  auto tri = [&](Vec3 a, Vec3 b, Vec3 c) {
    const uint32_t base = uint32_t(p.size());
    p.insert(p.end(), {a, b, c});
    t.emplace_back(base, base + 1, base + 2);
  };
  for (int i = 0; i < 40; ++i) {
    const float z = 0.025f * float(i);
    const float w = 0.002f;
    tri(Vec3(0, 0, z), Vec3(1, 1, z), Vec3(1 - w, 1, z + w));      // along the main diagonal
    tri(Vec3(1, 0, z + 0.01f), Vec3(0, 1, z + 0.01f), Vec3(w, 1, z + 0.01f + w));  // along the other
  }
  Rng rng(3);
  for (int i = 0; i < 400; ++i) {
    const Vec3 c(rng.uniform(), rng.uniform(), rng.uniform());
    const float s = 0.01f;
    tri(c, c + Vec3(s, 0, 0), c + Vec3(0, s, s));
  }
  return Scene(std::move(p), std::move(t), "crossing_slivers");
}

BvhBuildOptions sbvh_options() {
  BvhBuildOptions o;
  o.builder = BvhBuilderKind::Sbvh;
  return o;
}

/// build_bvh_tree()'s guarantees for sbvh: every valid triangle in at least one leaf, never
/// twice in one leaf, children inside their parent, leaf sizes, depth, and every point of a
/// triangle (sampled) inside the box of some leaf that holds it.
void expect_valid_spatial_tree(const BuildTree& tree, const Scene& scene, int leaf_size) {
  std::vector<std::vector<uint32_t>> leaves_of(scene.triangle_count());
  expect_valid_tree_shape(tree, leaf_size, [&](uint32_t i, const BuildNode& n) {
    std::set<uint32_t> in_leaf;
    for (uint32_t k = n.first; k < n.first + n.count; ++k) {
      EXPECT_TRUE(in_leaf.insert(tree.prims[k]).second) << "triangle " << tree.prims[k] << " twice in leaf " << i;
      leaves_of[tree.prims[k]].push_back(i);
    }
  });
  if (tree.empty()) return;
  Rng rng(9);
  for (uint32_t prim : scene.valid_prims()) {
    ASSERT_FALSE(leaves_of[prim].empty()) << "triangle " << prim << " lost";
    for (int s = 0; s < 8; ++s) {
      float a = rng.uniform(), b = rng.uniform();
      if (a + b > 1.0f) {
        a = 1.0f - a;
        b = 1.0f - b;
      }
      if (s < 3) a = b = 0.0f;  // the vertices themselves, exactly
      const Vec3 v0 = scene.vertex(prim, s < 3 ? s : 0), v1 = scene.vertex(prim, 1), v2 = scene.vertex(prim, 2);
      const Vec3 q = v0 + a * (v1 - v0) + b * (v2 - v0);
      bool inside = false;
      for (uint32_t leaf : leaves_of[prim]) {
        const Aabb& box = tree.nodes[leaf].box;
        // The float sample is within a few ulps of the triangle: allow that much.
        const Vec3 slack = 1e-6f * (glm::abs(q) + Vec3(1e-3f));
        inside = inside || (glm::all(glm::lessThanEqual(box.min - slack, q)) && glm::all(glm::lessThanEqual(q, box.max + slack)));
      }
      EXPECT_TRUE(inside) << "a point of triangle " << prim << " is in none of its leaves";
    }
  }
}

TEST(SpatialSplits, CrossingSliversAreSplitAndCostLessThanBinnedSah) {
  const Scene scene = crossing_slivers();
  const size_t n = scene.valid_prims().size();
  for (const char* width : {"width=2", "width=4"}) {
    SCOPED_TRACE(width);
    auto sbvh = build_structure("bvh", scene, {"builder=sbvh", width});
    auto binned = build_structure("bvh", scene, {"builder=binned_sah", width});
    ASSERT_TRUE(sbvh && binned);
    const BuildStats s = sbvh.value()->build_stats(), b = binned.value()->build_stats();
    EXPECT_EQ(s.prims, n);
    EXPECT_GT(s.prim_references, n) << "no spatial split";
    EXPECT_EQ(b.prim_references, n);
    EXPECT_LT(s.sah_cost, 0.9 * b.sah_cost) << "sbvh " << s.sah_cost << " binned " << b.sah_cost;
  }
  // The recorded steps name the spatial splits.
  BuildRecorder recorder;
  auto recorded = build_structure("bvh", scene, {"builder=sbvh", "width=2"}, Kernel::Watertight, nullptr, &recorder);
  ASSERT_TRUE(recorded);
  // The replay counts every reference of the duplicated triangles and ends at the tree's cost.
  BuildReplay replay(recorder.trace());
  replay.seek(replay.steps());
  const BuildStats rs = recorded.value()->build_stats();
  EXPECT_EQ(replay.references(), rs.prim_references);
  EXPECT_GT(replay.references(), n);
  EXPECT_NEAR(replay.sah_cost(1.0, 1.0), rs.sah_cost, 1e-6 * rs.sah_cost);
  size_t spatial = 0, duplicated = 0;
  std::vector<uint32_t> node_refs;  // by node id: the references of its Node step
  for (const BuildEvent& e : recorder.trace().events) {
    if (e.kind == BuildEventKind::Node) {
      node_refs.resize(std::max<size_t>(node_refs.size(), e.node + 1));
      node_refs[e.node] = e.list_count;
    }
    if (e.kind != BuildEventKind::Split || e.values[1] != 1.0f) continue;
    ++spatial;
    duplicated += e.count;
    ASSERT_LT(e.node, node_refs.size());
    EXPECT_EQ(e.a + e.b, node_refs[e.node] + e.count) << "left + right = the node's references + those on both sides";
    EXPECT_NE(describe_build_event(recorder.trace(), e).find("spatial split"), std::string::npos);
  }
  EXPECT_GT(spatial, 0u);
  EXPECT_GT(duplicated, 0u);
  expect_valid_spatial_tree(build_bvh_tree(scene, sbvh_options()), scene, 4);
}

TEST(SpatialSplits, ClippedBoxesContainTheTrianglesPartOnEachSide) {
  Rng rng(21);
  size_t checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // Triangles of every shape and scale, some with vertices exactly on the plane.
    const float scale = std::pow(10.0f, rng.uniform(-3.0f, 3.0f));
    const Vec3 offset = scale * 10.0f * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    Vec3 v[3];
    for (Vec3& p : v) p = offset + scale * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const int axis = int(rng.next_u64() % 3);
    Aabb tri_box;
    for (const Vec3& p : v) tri_box.extend(p);
    float pos = tri_box.min[axis] + rng.uniform() * (tri_box.max[axis] - tri_box.min[axis]);
    if (trial % 10 == 0) pos = v[trial % 3][axis];  // through a vertex
    if (trial % 37 == 0) v[1][axis] = v[2][axis] = v[0][axis], pos = v[0][axis], tri_box = Aabb{};  // in the plane
    if (tri_box.empty())
      for (const Vec3& p : v) tri_box.extend(p);
    const TriangleSplit s = split_triangle_box(v[0], v[1], v[2], tri_box, axis, pos);
    // A second cut of the right part, as the chopping into bins does: its region is the slab.
    const float pos2 = pos + 0.5f * (tri_box.max[axis] - pos);
    const TriangleSplit s2 = s.has_right ? split_triangle_box(v[0], v[1], v[2], s.right, axis, pos2) : TriangleSplit{};
    for (const Aabb* b : {&s.left, &s.right, &s2.left, &s2.right})
      if (!b->empty()) {
        EXPECT_TRUE(tri_box.contains(*b)) << "grew beyond the reference's box";
      }
    for (int k = 0; k < 200; ++k) {
      double a = double(rng.uniform()), b = double(rng.uniform());
      if (a + b > 1.0) {
        a = 1.0 - a;
        b = 1.0 - b;
      }
      if (k < 3) a = b = 0.0;
      const DVec3 p0(v[k < 3 ? k : 0]), p1(v[1]), p2(v[2]);
      const DVec3 q = p0 + a * (p1 - p0) + b * (p2 - p0);
      const double tol = 1e-12 * (std::abs(q.x) + std::abs(q.y) + std::abs(q.z) + 1e-30);
      auto contains = [&](const Aabb& box) {
        for (int i = 0; i < 3; ++i)
          if (q[i] < double(box.min[i]) - tol || q[i] > double(box.max[i]) + tol) return false;
        return true;
      };
      if (q[axis] <= double(pos)) {
        ASSERT_TRUE(s.has_left) << "trial " << trial;
        EXPECT_TRUE(contains(s.left)) << "trial " << trial << " sample " << k;
      }
      if (q[axis] >= double(pos)) {
        ASSERT_TRUE(s.has_right) << "trial " << trial;
        EXPECT_TRUE(contains(s.right)) << "trial " << trial << " sample " << k;
        if (q[axis] <= double(pos2)) {
          EXPECT_TRUE(s2.has_left && contains(s2.left)) << "trial " << trial;
        }
        if (q[axis] >= double(pos2)) {
          EXPECT_TRUE(s2.has_right && contains(s2.right)) << "trial " << trial;
        }
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 100000u);
}

TEST(SpatialSplits, ATriangleOutsideTheReferencesBoxOnOneSideHasNoPartThere) {
  const Vec3 a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
  Aabb box;  // the reference's region: x in [2, 4]
  box.min = Vec3(2, 0, 0);
  box.max = Vec3(4, 2, 0);
  const TriangleSplit s = split_triangle_box(a, b, c, box, 0, 1.0f);
  EXPECT_FALSE(s.has_left);
  ASSERT_TRUE(s.has_right);
  EXPECT_TRUE(box.contains(s.right));
  // In the plane: both sides, flat boxes.
  const TriangleSplit flat = split_triangle_box(Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(1, 0, 1),
                                                Aabb{Vec3(1, 0, 0), Vec3(1, 1, 1)}, 0, 1.0f);
  EXPECT_TRUE(flat.has_left && flat.has_right);
  EXPECT_EQ(flat.left.min.x, 1.0f);
  EXPECT_EQ(flat.right.max.x, 1.0f);
}

/// Every configuration answers as the double-precision reference by docs/hits.md's rule
/// (the suite's oracle: the closest triangle, or one tied with it, at its distance), and no
/// triangle becomes the closest hit twice in one query (its duplicates).
TEST(SpatialSplits, SameHitsAsTheReference) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> configs = {
      {"bvh", {"builder=sbvh", "width=2", "traversal=ordered"}},
      {"bvh", {"builder=sbvh", "width=2", "traversal=dfs", "leaf_size=1"}},
      {"bvh", {"builder=sbvh", "width=4", "traversal=pqueue"}},
      {"bvh", {"builder=sbvh", "width=4", "sbvh_alpha=0", "sbvh_budget=4"}},
      {"spheretree", {"builder=sbvh", "traversal=ordered"}},
      {"spheretree", {"builder=sbvh", "traversal=pqueue", "leaf_size=1"}},
  };
  for (const char* key : {"sbvh:crossing_slivers", "procedural:cornell", "procedural:soup"}) {
    SCOPED_TRACE(key);
    const std::string k = key;
    const testing::Workload& w = testing::workload(
        k,
        [k] { return k == "sbvh:crossing_slivers" ? crossing_slivers() : make_procedural_scene(k.substr(11)).value(); },
        20000, 64, 48);
    for (const auto& [structure, params] : configs) {
      std::string label = structure;
      for (const std::string& p : params) label += " " + p;
      SCOPED_TRACE(label);
      auto s = build_structure(structure, w.scene, params);
      ASSERT_TRUE(s) << s.error().message;
      const std::vector<Hit> got = trace_all(*s.value(), w.rays);
      std::string failures;
      EXPECT_EQ(testing::count_wrong(w, got, &failures), 0u) << failures;
      for (size_t i = 0; i < w.rays.size(); i += 37) {
        TraceRecorder rec;
        const Hit h = s.value()->intersect_traced(w.rays[i], rec);
        ASSERT_EQ(h.prim, got[i].prim);
        ASSERT_EQ(h.t, got[i].t);
        std::set<uint32_t> closest;
        for (const TraceEvent& e : rec.events()) {
          if (e.kind == TraceEventKind::NewClosest) {
            EXPECT_TRUE(closest.insert(e.prim).second) << "ray " << i << ": triangle " << e.prim << " twice";
          }
        }
      }
    }
  }
}

TEST(SpatialSplits, ReferenceBudgetIsRespected) {
  std::vector<Scene> scenes;
  scenes.push_back(crossing_slivers());
  scenes.push_back(make_procedural_scene("soup").value());
  for (const Scene& scene : scenes) {
    const size_t n = scene.valid_prims().size();
    for (float budget : {1.0f, 1.1f, 1.5f, 2.0f}) {
      SCOPED_TRACE(scene.name() + " budget " + std::to_string(budget));
      BvhBuildOptions o = sbvh_options();
      o.sbvh_budget = budget;
      o.sbvh_alpha = 0.0f;  // spatial splits wherever they pay
      const BuildTree tree = build_bvh_tree(scene, o);
      EXPECT_LE(double(tree.prims.size()), double(budget) * double(n));
      if (budget == 1.0f) {
        EXPECT_EQ(tree.prims.size(), n);
      }
      expect_valid_spatial_tree(tree, scene, o.leaf_size);
    }
  }
  auto s = build_structure("bvh", crossing_slivers(), {"builder=sbvh", "sbvh_budget=1.2"});
  ASSERT_TRUE(s);
  EXPECT_LE(double(s.value()->build_stats().refs_per_prim()), 1.2);
}

BuildTree build_with_threads(const Scene& scene, const BvhBuildOptions& o, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  return build_bvh_tree(scene, o);
}

TEST(SpatialSplits, TreeDoesNotDependOnTheThreadCountAndEqualsTheRecordedOne) {
  std::vector<Scene> scenes;
  scenes.push_back(make_procedural_scene("soup").value());
  scenes.push_back(make_procedural_scene("stadium").value());
  for (const Scene& scene : scenes) {
    for (int prims_per_test : {1, 4}) {
      SCOPED_TRACE(scene.name() + " prims_per_test " + std::to_string(prims_per_test));
      BvhBuildOptions o = sbvh_options();
      o.prims_per_test = prims_per_test;
      const BuildTree serial = build_with_threads(scene, o, 1);
      const BuildTree parallel = build_with_threads(scene, o, 4);
      expect_valid_spatial_tree(serial, scene, o.leaf_size);
      EXPECT_GT(serial.prims.size(), scene.valid_prims().size());
      expect_same_tree(serial, parallel);
      BuildRecorder recorder;
      const BuildTree recorded = build_bvh_tree(scene, o, nullptr, &recorder);
      expect_same_tree(serial, recorded);
    }
  }
}

TEST(SpatialSplits, RefitKeepsTheHitsAndCountsTrianglesOnce) {
  const Scene scene = make_procedural_scene("cornell").value();
  for (const char* width : {"width=2", "width=4"}) {
    auto s = build_structure("bvh", scene, {"builder=sbvh", width, "sbvh_alpha=0"});
    ASSERT_TRUE(s);
    ASSERT_GT(s.value()->build_stats().prim_references, s.value()->build_stats().prims);
    // The refitted boxes are the triangles' whole boxes: larger than the clipped ones, still bounds.
    testing::Workload w;
    w.scene = scene;
    std::vector<Vec3> moved = scene.positions();
    for (Vec3& p : moved) p += 0.02f * Vec3(std::sin(3.0f * p.y), std::cos(2.0f * p.x), std::sin(p.z));
    ASSERT_TRUE(w.scene.move_vertices(moved));
    ASSERT_TRUE(s.value()->refit(w.scene)) << width;
    w.rays = random_rays(w.scene.bounds(), 5000, 8);
    w.reference = testing::reference_hits(w.scene, w.rays);
    std::string failures;
    EXPECT_EQ(testing::count_wrong(w, trace_all(*s.value(), w.rays), &failures), 0u) << width << "\n" << failures;
    EXPECT_EQ(s.value()->build_stats().prims, scene.valid_prims().size());
  }
}

}  // namespace
}  // namespace accel
