// Every BVH builder of the table (bvh_builders.cpp): the SAH sweep over presorted lists
// builds exactly the tree of sorting every node (kept here as the reference), no builder's
// tree depends on the thread count, and every builder reports its progress and stops when
// cancelled.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "build_control.h"
#include "random.h"
#include "registry.h"
#include "scene.h"
#include "structures/bvh_builders.h"
#include "build_tree_compare.h"

namespace accel {
namespace {

using testing::expect_same_tree;

// ----------------------------------------------------------------------------
// The reference: the straightforward full sweep, three sorts per node
// ----------------------------------------------------------------------------

/// The SAH builder as it was before the presorted sweep (MacDonald & Booth 1990, the
/// lecture's "try all 3 axes"): every node sorts its references on each axis, sweeps, and
/// applies the winning axis order to its range. Serial and simple on purpose.
class ReferenceSweepBuilder {
 public:
  ReferenceSweepBuilder(const Scene& scene, const BvhBuildOptions& o) : o_(o) {
    for (uint32_t p : scene.valid_prims()) refs_.push_back({scene.triangle_bounds(p), scene.centroid(p), p});
  }

  BuildTree build() {
    BuildTree tree;
    if (refs_.empty()) return tree;
    out_ = &tree;
    tree.root = build_node(0, refs_.size(), 0);
    for (const Ref& r : refs_) tree.prims.push_back(r.prim);
    return tree;
  }

 private:
  struct Ref {
    Aabb box;
    Vec3 centroid;
    uint32_t prim;
  };
  struct Split {
    bool valid = false;
    size_t mid = 0;
    float cost = 0.0f;
  };

  uint32_t build_node(size_t begin, size_t end, int depth) {
    const uint32_t index = uint32_t(out_->nodes.size());
    out_->nodes.emplace_back();
    Aabb box;
    for (size_t i = begin; i < end; ++i) box.extend(refs_[i].box);
    out_->nodes[index].box = box;
    const size_t count = end - begin;
    Split split;
    if (count > 1) split = sweep_split(begin, end, box);
    const bool small = count <= size_t(o_.leaf_size);
    if (count <= 1 || (small && (!split.valid || split.cost >= o_.leaf_cost(count))) || depth >= kMaxBvhDepth - 1) {
      out_->nodes[index].first = uint32_t(begin);
      out_->nodes[index].count = uint32_t(count);
      return index;
    }
    EXPECT_TRUE(split.valid && split.mid > begin && split.mid < end);  // the sweep tries every position
    const uint32_t left = build_node(begin, split.mid, depth + 1);
    const uint32_t right = build_node(split.mid, end, depth + 1);
    out_->nodes[index].left = left;
    out_->nodes[index].right = right;
    return index;
  }

  Split sweep_order(const std::vector<uint32_t>& order, size_t begin, float parent_area) {
    const size_t n = order.size();
    std::vector<float> right_area(n);
    Aabb acc;
    for (size_t i = n; i-- > 1;) {
      acc.extend(refs_[begin + order[i]].box);
      right_area[i] = acc.area();
    }
    Split best;
    acc = Aabb{};
    const float inv = parent_area > 0.0f ? 1.0f / parent_area : 1.0f;
    for (size_t i = 1; i < n; ++i) {
      acc.extend(refs_[begin + order[i - 1]].box);
      const float cost = o_.ct + (acc.area() * o_.leaf_cost(i) + right_area[i] * o_.leaf_cost(n - i)) * inv;
      if (!best.valid || cost < best.cost) best = {true, begin + i, cost};
    }
    return best;
  }

  Split sweep_split(size_t begin, size_t end, const Aabb& box) {
    const size_t n = end - begin;
    Split best;
    std::vector<uint32_t> order(n), best_order;
    for (int axis = 0; axis < 3; ++axis) {
      std::iota(order.begin(), order.end(), 0u);
      std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const Ref &ra = refs_[begin + a], &rb = refs_[begin + b];
        return ra.centroid[axis] < rb.centroid[axis] || (ra.centroid[axis] == rb.centroid[axis] && ra.prim < rb.prim);
      });
      const Split s = sweep_order(order, begin, box.area());
      if (s.valid && (!best.valid || s.cost < best.cost)) {
        best = s;
        best_order = order;
      }
    }
    if (best.valid) {
      std::vector<Ref> sorted;
      for (uint32_t k : best_order) sorted.push_back(refs_[begin + k]);
      std::copy(sorted.begin(), sorted.end(), refs_.begin() + long(begin));
    }
    return best;
  }

  const BvhBuildOptions& o_;
  std::vector<Ref> refs_;
  BuildTree* out_ = nullptr;
};

// ----------------------------------------------------------------------------
// Scenes
// ----------------------------------------------------------------------------

/// Random small triangles in a few clusters, with some long thin ones.
Scene clustered_soup(size_t count, uint64_t seed) {
  Rng rng(seed);
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (size_t i = 0; i < count; ++i) {
    const float size = i % 13 == 0 ? 0.6f : 0.02f;
    const Vec3 c = Vec3(float(i % 4), float((i / 4) % 3), 0.0f) + Vec3(rng.uniform(), rng.uniform(), rng.uniform());
    const uint32_t base = uint32_t(p.size());
    for (int k = 0; k < 3; ++k) p.push_back(c + size * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
    t.emplace_back(base, base + 1, base + 2);
  }
  return Scene(std::move(p), std::move(t));
}

/// Many copies of one triangle (every centre equal) among copies of a few others.
Scene equal_centroids() {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 2}, {3, 2, 2}, {2, 3, 2.5f}};
  std::vector<UVec3> t;
  for (int i = 0; i < 3000; ++i) t.emplace_back(i % 3 == 0 ? UVec3(3, 4, 5) : UVec3(0, 1, 2));
  return Scene(std::move(p), std::move(t));
}

/// Triangles whose centres lie on a coarse lattice: ties on every axis, in every node.
Scene lattice() {
  Rng rng(5);
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 c(float(rng.next_u64() % 6), float(rng.next_u64() % 5), float(rng.next_u64() % 4));
    const float s = 0.1f + 0.1f * float(i % 3);
    const uint32_t base = uint32_t(p.size());
    // The box is c +- s on every axis, so the centre is the lattice point for every s.
    p.insert(p.end(), {c + Vec3(-s, -s, -s), c + Vec3(s, -s, 0), c + Vec3(0, s, s)});
    t.emplace_back(base, base + 1, base + 2);
  }
  return Scene(std::move(p), std::move(t));
}

/// Triangles in the planes x = +0 and x = -0 (and the same for y): centres and box faces
/// that compare equal but differ in the sign bit, where min/max order shows.
Scene signed_zeros() {
  Rng rng(9);
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (int i = 0; i < 2000; ++i) {
    const float zero = i % 2 ? -0.0f : 0.0f;
    const float a = rng.uniform(-1, 1), b = rng.uniform(-1, 1);
    const uint32_t base = uint32_t(p.size());
    if (i % 4 < 2) p.insert(p.end(), {{zero, a, b}, {zero, a + 0.1f, b}, {zero, a, b + 0.1f}});
    else p.insert(p.end(), {{a, zero, b}, {a + 0.1f, zero, b}, {a, zero, b + 0.1f}});
    t.emplace_back(base, base + 1, base + 2);
  }
  return Scene(std::move(p), std::move(t));
}

const Scene& stadium() {
  static const Scene scene = make_procedural_scene("stadium").value();
  return scene;
}

/// Big enough that every builder reports many times and a build takes a while to cancel.
const Scene& big_soup() {
  static const Scene scene = clustered_soup(120000, 3);
  return scene;
}

// ----------------------------------------------------------------------------
// Helpers
// ----------------------------------------------------------------------------

/// Builds with exactly `threads` threads (also on a machine with fewer cores).
BuildTree build_in_arena(const Scene& scene, const BvhBuildOptions& o, int threads) {
  tbb::global_control allow(tbb::global_control::max_allowed_parallelism, size_t(threads));
  tbb::task_arena arena(threads);
  BuildTree tree;
  arena.execute([&] { tree = build_bvh_tree(scene, o); });
  return tree;
}

/// A builder configuration: the option values and a label.
struct BuilderCase {
  std::string label;
  BvhBuildOptions options;
};

/// Every builder of the table with its default options, and the options that change a
/// builder's code path (the median's axis rules, the sweep's leaf cost table).
std::vector<BuilderCase> builder_cases() {
  std::vector<BuilderCase> cases;
  for (const BvhBuilderInfo& row : bvh_builder_table()) {
    BvhBuildOptions o;
    o.builder = row.kind;
    cases.push_back({row.name, o});
  }
  const auto add = [&](std::string label, BvhBuilderKind kind, auto&& tweak) {
    BvhBuildOptions o;
    o.builder = kind;
    tweak(o);
    cases.push_back({std::move(label), o});
  };
  add("sah leaf 1", BvhBuilderKind::Sah, [](BvhBuildOptions& o) { o.leaf_size = 1; });
  add("sah 4 per test", BvhBuilderKind::Sah, [](BvhBuildOptions& o) { o.prims_per_test = 4; });
  add("median x", BvhBuilderKind::Median, [](BvhBuildOptions& o) { o.axis = MedianAxis::X; });
  add("median round robin", BvhBuilderKind::Median, [](BvhBuildOptions& o) { o.axis = MedianAxis::RoundRobin; });
  return cases;
}

// ----------------------------------------------------------------------------
// Tests
// ----------------------------------------------------------------------------

TEST(BvhSweep, PresortedSweepBuildsTheTreeOfSortingEveryNode) {
  std::vector<std::pair<std::string, Scene>> scenes;
  scenes.emplace_back("sphere", make_procedural_scene("sphere").value());
  scenes.emplace_back("cornell", make_procedural_scene("cornell").value());
  scenes.emplace_back("soup", make_procedural_scene("soup").value());
  scenes.emplace_back("clustered soup", clustered_soup(6000, 1));
  scenes.emplace_back("equal centroids", equal_centroids());
  scenes.emplace_back("lattice", lattice());
  scenes.emplace_back("signed zeros", signed_zeros());
  struct Variant {
    const char* label;
    int leaf_size, prims_per_test;
    float ct, ci;
  };
  const Variant variants[] = {{"default", 4, 1, 1.0f, 1.0f},
                              {"leaf 1", 1, 1, 1.0f, 1.0f},
                              {"leaf 8, 4 per test", 8, 4, 1.0f, 1.0f},
                              {"cheap steps", 6, 1, 0.1f, 3.0f}};
  for (const auto& [name, scene] : scenes) {
    for (const Variant& v : variants) {
      SCOPED_TRACE(name + ", " + v.label);
      BvhBuildOptions o;
      o.builder = BvhBuilderKind::Sah;
      o.leaf_size = v.leaf_size;
      o.prims_per_test = v.prims_per_test;
      o.ct = v.ct;
      o.ci = v.ci;
      const BuildTree reference = ReferenceSweepBuilder(scene, o).build();
      ASSERT_FALSE(reference.empty());
      expect_same_tree(reference, build_in_arena(scene, o, 1));
      expect_same_tree(reference, build_in_arena(scene, o, 4));
    }
  }
}

TEST(BvhSweep, TreeDoesNotDependOnTheThreadCount) {
  // Both scenes have subtrees far above the task threshold (the parallel path).
  const std::vector<std::pair<std::string, const Scene*>> scenes = {{"stadium", &stadium()},
                                                                    {"soup 120k", &big_soup()}};
  for (const auto& [name, scene] : scenes) {
    for (const BuilderCase& c : builder_cases()) {
      SCOPED_TRACE(name + ", " + c.label);
      const BuildTree serial = build_in_arena(*scene, c.options, 1);
      ASSERT_FALSE(serial.empty());
      expect_same_tree(serial, build_in_arena(*scene, c.options, 4));
    }
  }
}

TEST(BvhSweep, EveryBuilderReportsProgressInsideItsSpan) {
  for (const BvhBuilderInfo& row : bvh_builder_table()) {
    const char* builder = row.name;
    SCOPED_TRACE(builder);
    std::vector<double> seen;
    BuildControl control([&](double f) { seen.push_back(f); });
    auto s = build_structure("bvh", big_soup(), {std::string("builder=") + builder, "width=2"}, Kernel::Watertight,
                             &control);
    ASSERT_TRUE(s.ok()) << s.error().message;
    // The hierarchy maps the builder's progress to [0, 0.8] (hierarchy.h, build_impl).
    std::vector<double> inside;
    for (double f : seen)
      if (f > 0.0 && f < 0.8) inside.push_back(f);
    EXPECT_GE(inside.size(), 5u) << "the builder reported too rarely";
    for (size_t i = 1; i < inside.size(); ++i) EXPECT_LT(inside[i - 1], inside[i]) << "report " << i;
    for (size_t i = 1; i < seen.size(); ++i) EXPECT_LE(seen[i - 1], seen[i]) << "report " << i << " went back";
    EXPECT_EQ(seen.back(), 1.0);
  }
}

TEST(BvhSweep, CancelFromTheProgressCallbackStopsTheBuildQuickly) {
  using Clock = std::chrono::steady_clock;
  for (const BuilderCase& c : builder_cases()) {
    SCOPED_TRACE(c.label);
    const Clock::time_point full_start = Clock::now();
    const BuildTree full = build_bvh_tree(big_soup(), c.options);
    const double full_ms = std::chrono::duration<double, std::milli>(Clock::now() - full_start).count();

    std::vector<double> seen;
    size_t cancel_at = 0;
    Clock::time_point cancelled_at;
    BuildControl* self = nullptr;
    BuildControl control([&](double f) {
      seen.push_back(f);
      if (f >= 0.2 && !self->cancelled()) {
        cancel_at = seen.size();
        cancelled_at = Clock::now();
        self->cancel();
      }
    });
    self = &control;
    // The span the hierarchy gives its builder; called directly so only the builder reports.
    ProgressSpan span(&control, 0.0, 0.8);
    const BuildTree partial = build_bvh_tree(big_soup(), c.options, &span);
    const double tail_ms = std::chrono::duration<double, std::milli>(Clock::now() - cancelled_at).count();
    ASSERT_TRUE(control.cancelled()) << "the build never reached 0.2";
    EXPECT_EQ(seen.size(), cancel_at) << "reported on after the cancel";
    EXPECT_LT(partial.nodes.size(), full.nodes.size()) << "the cancelled build finished the tree";
    // Quickly: the rest of the build after the cancel is a small part of a whole build.
    EXPECT_LT(tail_ms, 0.5 * full_ms) << "full build " << full_ms << " ms";
  }
}

}  // namespace
}  // namespace accel
