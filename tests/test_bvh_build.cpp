// The parallel binned SAH builder (bvh_binned_builder.cpp): its tree must not depend on the
// thread count, and it keeps the guarantees of build_bvh_tree() on large inputs.
#include <algorithm>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "random.h"
#include "scene.h"
#include "structures/bvh_builders.h"
#include "structures/hierarchy_params.h"
#include "build_tree_compare.h"

namespace accel {
namespace {

using testing::expect_same_tree;
using testing::expect_valid_tree_shape;

/// Random triangles: a few clusters of small ones (so the SAH has structure to find) and a
/// sprinkling of long thin ones; large enough for parallel tasks and parallel binning.
Scene generated_soup(size_t count, uint64_t seed) {
  Rng rng(seed);
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (size_t i = 0; i < count; ++i) {
    const float size = i % 17 == 0 ? 0.5f : 0.01f;
    const Vec3 cluster(float(i % 5), float((i / 5) % 3), 0.0f);
    const Vec3 c = cluster + Vec3(rng.uniform(), rng.uniform(), rng.uniform());
    const uint32_t base = uint32_t(p.size());
    for (int k = 0; k < 3; ++k)
      p.push_back(c + size * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
    t.emplace_back(base, base + 1, base + 2);
  }
  return Scene(std::move(p), std::move(t));
}

/// Many copies of one triangle (every centroid equal: the median fallback everywhere) next
/// to a grid of distinct ones.
Scene duplicates_and_grid() {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<UVec3> t(20000, UVec3(0, 1, 2));
  for (uint32_t i = 0; i < 20000; ++i) {
    const Vec3 c(float(i % 100) + 5.0f, float(i / 100), 0.0f);
    const uint32_t base = uint32_t(p.size());
    p.insert(p.end(), {c, c + Vec3(0.5f, 0, 0), c + Vec3(0, 0.5f, 0.1f)});
    t.emplace_back(base, base + 1, base + 2);
  }
  return Scene(std::move(p), std::move(t));
}

BuildTree build_with_threads(const Scene& scene, const BvhBuildOptions& o, int threads) {
  if (threads > 0) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    return build_bvh_tree(scene, o);
  }
  return build_bvh_tree(scene, o);
}

/// The guarantees of build_bvh_tree(), checked on the builder's own output.
void expect_valid_build_tree(const BuildTree& tree, const Scene& scene, int leaf_size) {
  std::vector<uint32_t> seen;
  expect_valid_tree_shape(tree, leaf_size, [&](uint32_t i, const BuildNode& n) {
    for (uint32_t k = n.first; k < n.first + n.count; ++k) {
      EXPECT_TRUE(n.box.contains(scene.triangle_bounds(tree.prims[k]))) << "leaf " << i;
      seen.push_back(tree.prims[k]);
    }
  });
  std::vector<uint32_t> valid = scene.valid_prims();
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, valid);  // valid_prims() is ascending: every valid triangle exactly once
}

// The builders' table is the one place a builder is named: every kind has one row, the
// names are distinct, and the `builder` parameter offers exactly the table's names in order.
TEST(BvhBuilderTable, OneRowPerBuilderDrivesTheParameter) {
  const auto rows = accel::bvh_builder_table();
  std::set<std::string> names;
  for (size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(size_t(rows[k].kind), k) << "rows in enum order";
    EXPECT_EQ(&accel::bvh_builder(rows[k].kind), &rows[k]);
    EXPECT_STREQ(accel::builder_name(rows[k].kind), rows[k].name);
    EXPECT_TRUE(names.insert(rows[k].name).second) << rows[k].name;
    EXPECT_GT(std::strlen(rows[k].label), 0u);
    EXPECT_GT(std::strlen(rows[k].help), 0u);
    EXPECT_NE(rows[k].build, nullptr);
  }
  for (const accel::ParamSpec& spec : accel::bvh_param_specs()) {
    if (spec.name != "builder") continue;
    ASSERT_EQ(spec.choices.size(), rows.size());
    for (size_t k = 0; k < rows.size(); ++k) {
      EXPECT_EQ(spec.choices[k], rows[k].name);
      EXPECT_NE(spec.doc.find(rows[k].help), std::string::npos) << rows[k].help;
    }
  }
}

TEST(BvhBinnedBuild, TreeDoesNotDependOnTheThreadCount) {
  std::vector<std::pair<std::string, Scene>> scenes;
  scenes.emplace_back("soup 80k", generated_soup(80000, 7));
  scenes.emplace_back("duplicates", duplicates_and_grid());
  scenes.emplace_back("stadium", make_procedural_scene("stadium").value());
  scenes.emplace_back("steps", load_obj(std::string(ACCEL_SOURCE_DIR) + "/scenes/steps.obj").value());
  for (const auto& [name, scene] : scenes) {
    for (int prims_per_test : {1, 4}) {
      for (int bins : {2, 16, 256}) {
        SCOPED_TRACE(name + " prims_per_test " + std::to_string(prims_per_test) + " bins " + std::to_string(bins));
        BvhBuildOptions o;
        o.builder = BvhBuilderKind::BinnedSah;
        o.bins = bins;
        o.prims_per_test = prims_per_test;
        const BuildTree serial = build_with_threads(scene, o, 1);
        const BuildTree two = build_with_threads(scene, o, 2);
        const BuildTree parallel = build_with_threads(scene, o, 0);
        expect_valid_build_tree(serial, scene, o.leaf_size);
        expect_same_tree(serial, two);
        expect_same_tree(serial, parallel);
      }
    }
  }
}

TEST(BvhBinnedBuild, LargeInputsKeepTheGuarantees) {
  const Scene scene = generated_soup(150000, 11);
  for (int leaf : {1, 4, 16}) {
    SCOPED_TRACE("leaf " + std::to_string(leaf));
    BvhBuildOptions o;
    o.builder = BvhBuilderKind::BinnedSah;
    o.leaf_size = leaf;
    expect_valid_build_tree(build_bvh_tree(scene, o), scene, leaf);
  }
}

}  // namespace
}  // namespace accel
