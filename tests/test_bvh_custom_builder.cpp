// A BVH builder that exists only in this test binary: the proof that a top-down builder is
// a splitter and a table row (docs/structures.md, "Adding a BVH builder"). It splits a node
// at the middle of the longest axis of its box. Registered at static initialisation
// (add_bvh_builder()), it is in the builders' table for every test of this binary, so the
// tests that iterate the table build and check it too (the suite against brute force in
// test_bvh.cpp and test_sphere_tree.cpp, the recorded builds of test_build_trace.cpp, the
// thread-count and cancel tests of test_bvh_sweep.cpp).
//
// Its construction listing is beside its row (kMiddleListing): the viewer puts the one
// recursion's lines around it.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "oracle.h"
#include "random.h"
#include "registry.h"
#include "scene.h"
#include "structure_suite.h"
#include "structures/bvh_builders.h"
#include "structures/bvh_top_down.h"
#include "test_support.h"

namespace accel {
namespace {

using namespace top_down;
using testing::four_walls;

/// Splits a node at the middle of its box's longest axis: a centre below it goes left.
/// InPlaceSplitter supplies the rest (the references, the box, the leaves, the median
/// fallback when a side comes out empty); no cost, so a small node is a leaf.
template <class Sink>
class MiddleSplitter : public InPlaceSplitter<MiddleSplitter<Sink>, Sink> {
 public:
  static constexpr bool kSahLeafRule = false;
  using Scratch = ScratchBase;
  using InPlaceSplitter<MiddleSplitter<Sink>, Sink>::InPlaceSplitter;

  Split split(Scratch&, RefRange& w, const Aabb& box, int, [[maybe_unused]] uint32_t id) {
    std::vector<PrimRef>& refs = this->refs_;
    const int axis = box.longest_axis();
    const float middle = box.center()[axis];
    const auto mid = std::partition(refs.begin() + long(w.begin), refs.begin() + long(w.end),
                                    [&](const PrimRef& r) { return r.centroid[axis] < middle; });
    if constexpr (Sink::kRecords) this->sink_.axis(id, axis, unit_axis(axis));
    Split s;
    s.valid = true;
    s.mid = size_t(mid - refs.begin());
    s.cost = std::nanf("");  // no SAH: the recorded step shows plane_cost
    s.plane_axis = axis;
    s.plane_pos = middle;
    return s;
  }
};

BuildTree build_middle_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                            BuildRecorder* recorder) {
  return build_top_down<MiddleSplitter>(scene, options, progress, recorder);
}

constexpr ListingLine kMiddleLines[] = {
    {"axis", "    axis = the longest axis of the node's box"},
    {"split", "    split at the box's middle on it (a side empty: at the median)"},
};
constexpr BuilderListing kMiddleListing{"BVH: top-down, middle of the box (test)", kMiddleLines};

const BvhBuilderKind kMiddle = add_bvh_builder({BvhBuilderKind{}, "test_middle", "middle (test)",
                                                "the middle of the node box's longest axis (test only)", false, true,
                                                &kMiddleListing, build_middle_tree});

TEST(BvhCustomBuilder, IsARowOfTheTableAndAChoiceOfTheParameter) {
  EXPECT_STREQ(builder_name(kMiddle), "test_middle");
  EXPECT_EQ(bvh_builder(kMiddle).build, &build_middle_tree);
  EXPECT_EQ(&bvh_builder_table().back(), &bvh_builder(kMiddle));
  auto built = build_structure("bvh", make_procedural_scene("cornell").value(), {"builder=test_middle"});
  ASSERT_TRUE(built) << built.error().message;
}

// The root's box is x in [0, 3] (the longest axis): its middle 1.5 puts walls 0 and 1 left;
// each half's middle separates its two walls.
TEST(BvhCustomBuilder, SplitsAtTheMiddleOfTheLongestAxis) {
  BvhBuildOptions o;
  o.builder = kMiddle;
  o.leaf_size = 1;
  const BuildTree tree = build_bvh_tree(four_walls(), o);
  ASSERT_EQ(tree.nodes.size(), 7u);
  EXPECT_EQ(tree.prims, (std::vector<uint32_t>{0, 1, 2, 3}));
  const BuildNode& root = tree.nodes[tree.root];
  ASSERT_EQ(root.count, 0u);
  EXPECT_EQ(tree.nodes[root.left].box.max.x, 1.0f);
  EXPECT_EQ(tree.nodes[root.right].box.min.x, 2.0f);
}

// Every centre equal: no centre is below the middle, so every node falls back to the median
// and the tree is still balanced.
TEST(BvhCustomBuilder, FallsBackToTheMedianWhenASideIsEmpty) {
  std::vector<UVec3> t(64, UVec3(0, 1, 2));
  const Scene scene({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, std::move(t));
  BvhBuildOptions o;
  o.builder = kMiddle;
  o.leaf_size = 1;
  const BuildTree tree = build_bvh_tree(scene, o);
  EXPECT_EQ(tree.nodes.size(), 127u);
  auto built = build_structure("bvh", scene, {"builder=test_middle", "leaf_size=1", "width=2"});
  ASSERT_TRUE(built);
  EXPECT_EQ(built.value()->build_stats().max_depth, 6);
}

// Exact answers against brute force: random rays through soups and meshes, with the binary
// tree, both wide layouts and the sphere tree, hit exactly where brute force hits, and
// every answer of either is correct by docs/hits.md's rule against the double-precision
// reference (the oracle of every structure test: a triangle tied with the nearest, e.g.
// across a shared edge, is correct too, and the tree's leaf kernel may round t differently).
TEST(BvhCustomBuilder, AnswersExactlyAsBruteForce) {
  for (const char* name : {"soup", "stadium", "cornell", "sphere"}) {
    const Scene scene = make_procedural_scene(name).value();
    auto brute = build_structure("brute", scene, {});
    ASSERT_TRUE(brute);
    const std::vector<std::pair<std::string, std::vector<std::string>>> configs = {
        {"bvh", {"builder=test_middle", "width=2"}},
        {"bvh", {"builder=test_middle", "width=4", "leaf_size=1"}},
        {"bvh", {"builder=test_middle", "width=8", "traversal=ordered"}},
        {"spheretree", {"builder=test_middle", "traversal=pqueue"}},
    };
    for (const auto& [structure, params] : configs) {
      SCOPED_TRACE(std::string(name) + " " + structure + " " + params.back());
      auto built = build_structure(structure, scene, params);
      ASSERT_TRUE(built) << built.error().message;
      const Aabb box = scene.bounds();
      Rng rng(17);
      size_t hits = 0;
      for (int i = 0; i < 3000; ++i) {
        Ray r;
        r.org = box.center() + box.extent() * Vec3(rng.uniform(-0.7f, 0.7f), rng.uniform(-0.7f, 0.7f),
                                                   rng.uniform(-0.7f, 0.7f));
        r.dir = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        const Hit want = brute.value()->intersect(r), got = built.value()->intersect(r);
        ASSERT_EQ(want.valid(), got.valid()) << "ray " << i;
        if (!want.valid()) continue;
        const testing::ReferenceHit ref = testing::reference_closest(scene, r);
        std::string why;
        EXPECT_TRUE(testing::hit_is_correct(scene, r, got, ref, &why)) << "ray " << i << ": " << why;
        EXPECT_TRUE(testing::hit_is_correct(scene, r, want, ref, &why)) << "ray " << i << " (brute): " << why;
        ++hits;
      }
      EXPECT_GT(hits, 500u);
    }
  }
}

}  // namespace

namespace testing {
// The structure suite (identical answers to the reference on procedural, shared and edge
// scenes; recording never changes the answer) with the test builder.
INSTANTIATE_TEST_SUITE_P(CustomBuilder, StructureVsReference,
                         ::testing::Values(SuiteCase{"bvh", {"builder=test_middle", "width=2", "leaf_size=1"}},
                                           SuiteCase{"spheretree", {"builder=test_middle", "traversal=ordered"}}),
                         suite_case_name);
}  // namespace testing

}  // namespace accel
