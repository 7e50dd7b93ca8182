// Parameters: one declaration (ParamTable) gives the specs, the defaults (from the options
// struct), typed values and the options struct; the CLI's error messages name the
// parameter and its range.
#include <gtest/gtest.h>

#include "params.h"
#include "registry.h"
#include "structures/hierarchy_params.h"
#include "structures/kd_tree.h"
#include "structures/uniform_grid.h"

namespace accel {
namespace {

enum class Rule { Middle, Median, Sah };

/// A made-up options struct with one field of every parameter type, nested like a real one.
struct TestOptions {
  struct Build {
    int leaf_size = 4;
    float lambda = 1.0f;
    Rule split = Rule::Sah;
  } build;
  std::array<int, 3> res{8, 8, 8};
  bool flag = true;
};

const ParamTable<TestOptions>& table() {
  using O = TestOptions;
  static const auto t =
      ParamTable<O>()
          .integer("leaf_size", [](O& o) -> auto& { return o.build.leaf_size; }, 1, 64, "max triangles per leaf")
          .number("lambda", [](O& o) -> auto& { return o.build.lambda; }, 0.01, 100, "cells per cbrt(N)")
          .choice("split", [](O& o) -> auto& { return o.build.split; },
                  std::vector<std::pair<std::string, Rule>>{
                      {"middle", Rule::Middle}, {"median", Rule::Median}, {"sah", Rule::Sah}},
                  "split rule")
          .int3("res", &O::res, 1, 1024, "grid resolution")
          .choice("flag", &O::flag, std::vector<std::pair<std::string, bool>>{{"off", false}, {"on", true}}, "a switch");
  return t;
}

std::vector<ParamSpec> specs() { return table().specs(); }

TEST(Params, DefaultsComeFromTheOptionsStruct) {
  const auto s = specs();
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[0].default_value, "4");
  EXPECT_EQ(s[1].default_value, "1");
  EXPECT_EQ(s[2].default_value, "sah");
  EXPECT_EQ(s[2].choices, (std::vector<std::string>{"middle", "median", "sah"}));
  EXPECT_EQ(s[3].default_value, "8,8,8");
  EXPECT_EQ(s[4].default_value, "on");
  EXPECT_EQ(std::get<int>(s[2].default_typed), 2);  // index of "sah"
  const TestOptions o = table().apply(ParamSet(s));
  EXPECT_EQ(o.build.leaf_size, 4);
  EXPECT_EQ(o.build.split, Rule::Sah);
  EXPECT_TRUE(o.flag);
}

TEST(Params, DefaultsAndOverrides) {
  auto p = ParamSet::parse(specs(), {"leaf_size=8", "res=4,5,6", "split=median", "flag=off"}, "kdtree");
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p.value().get_int("leaf_size"), 8);
  EXPECT_DOUBLE_EQ(p.value().get_float("lambda"), 1.0);
  EXPECT_EQ(p.value().get_choice("split"), "median");
  EXPECT_EQ(p.value().get_choice_index("split"), 1);
  EXPECT_EQ(p.value().get_int3("res"), (std::array<int, 3>{4, 5, 6}));
  EXPECT_TRUE(p.value().is_set("leaf_size"));
  EXPECT_FALSE(p.value().is_set("lambda"));
  EXPECT_EQ(p.value().to_string(), "leaf_size=8,split=median,res=4,5,6,flag=off");
  const TestOptions o = table().apply(p.value());
  EXPECT_EQ(o.build.leaf_size, 8);
  EXPECT_EQ(o.build.split, Rule::Median);
  EXPECT_EQ(o.res, (std::array<int, 3>{4, 5, 6}));
  EXPECT_FALSE(o.flag);
}

// A 2D scene's defaults (issue #50): the fields of the table's 2D options struct that differ
// from Options{} become ParamSpec::planar_default; set_planar() swaps them in for the keys
// not given, reset() goes back to the mode's default, and an explicit value always wins.
TEST(Params, PlanarDefaultsReplaceOnlyTheKeysNotGiven) {
  using O = TestOptions;
  O flat;
  flat.build.leaf_size = 1;
  flat.build.split = Rule::Middle;
  const auto t = ParamTable<O>(flat)
                     .integer("leaf_size", [](O& o) -> auto& { return o.build.leaf_size; }, 1, 64, "leaf")
                     .number("lambda", [](O& o) -> auto& { return o.build.lambda; }, 0.01, 100, "cells")
                     .choice("split", [](O& o) -> auto& { return o.build.split; },
                             std::vector<std::pair<std::string, Rule>>{
                                 {"middle", Rule::Middle}, {"median", Rule::Median}, {"sah", Rule::Sah}},
                             "rule");
  const std::vector<ParamSpec>& s = t.specs();
  EXPECT_EQ(s[0].default_value, "4");  // the 3D default stays the default
  ASSERT_TRUE(s[0].planar_default);
  EXPECT_EQ(std::get<int>(*s[0].planar_default), 1);
  EXPECT_FALSE(s[1].planar_default);   // the same in 2D: none
  EXPECT_EQ(std::get<int>(s[2].default_for(true)), 0);  // "middle"
  EXPECT_EQ(std::get<int>(s[2].default_for(false)), 2);  // "sah"

  auto p = ParamSet::parse(s, {"split=median"}).value();
  p.set_planar(true);
  EXPECT_EQ(p.get_int("leaf_size"), 1);
  EXPECT_EQ(p.get_choice("split"), "median");  // given: kept
  EXPECT_EQ(p.to_string(), "split=median");    // the 2D defaults are no explicit values
  p.reset("split");
  EXPECT_EQ(p.get_choice("split"), "middle");
  EXPECT_EQ(t.apply(p).build.leaf_size, 1);
  p.set_planar(false);
  EXPECT_EQ(p.get_int("leaf_size"), 4);
  EXPECT_EQ(p.get_choice("split"), "sah");
  EXPECT_EQ(ParamTable<O>().integer("leaf_size", [](O& o) -> auto& { return o.build.leaf_size; }, 1, 64, "leaf")
                .specs()[0]
                .planar_default,
            std::nullopt);  // a table without 2D defaults
}

// The viewer's widgets set typed values: a double is kept to the last bit, not rounded
// through text (the old "%.4g" round trip turned 0.123456789 into 0.1235).
TEST(Params, TypedValuesAreKeptExactly) {
  ParamSet p(specs(), "test");
  ASSERT_TRUE(p.set_value("lambda", ParamValue(0.123456789)));
  EXPECT_EQ(p.get_float("lambda"), 0.123456789);
  EXPECT_EQ(p.text("lambda"), "0.123456789");
  auto back = ParamSet::parse(specs(), p.explicit_key_values(), "test");
  ASSERT_TRUE(back);
  EXPECT_EQ(back.value().get_float("lambda"), 0.123456789);
  EXPECT_TRUE(back.value() == p);
  p.reset("lambda");
  EXPECT_FALSE(p.is_set("lambda"));
  EXPECT_DOUBLE_EQ(p.get_float("lambda"), 1.0);
}

TEST(Params, TypedValuesAreValidated) {
  ParamSet p(specs(), "test");
  EXPECT_FALSE(p.set_value("leaf_size", ParamValue(0)));
  EXPECT_FALSE(p.set_value("leaf_size", ParamValue(2.0)));  // wrong type
  EXPECT_FALSE(p.set_value("split", ParamValue(3)));        // no fourth choice
  EXPECT_FALSE(p.set_value("res", ParamValue(std::array<int, 3>{1, 0, 1})));
  EXPECT_FALSE(p.set_value("lambda", ParamValue(std::nan(""))));
  EXPECT_FALSE(p.set_value("nope", ParamValue(1)));
  EXPECT_EQ(p.to_string(), "");  // nothing invalid got in
  const Status s = p.set_value("leaf_size", ParamValue(99));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().message, "test parameter 'leaf_size' = '99' is invalid: expected an integer in [1, 64]");
}

TEST(Params, ErrorsNameParameterAndRange) {
  auto expect_error = [](std::vector<std::string> kv, const std::string& text) {
    auto p = ParamSet::parse(specs(), kv, "kdtree");
    ASSERT_FALSE(p) << kv[0];
    EXPECT_NE(p.error().message.find(text), std::string::npos) << p.error().message;
  };
  expect_error({"leaf_size=0"}, "parameter 'leaf_size' = '0' is invalid: expected an integer in [1, 64]");
  expect_error({"leaf_size=2.5"}, "'leaf_size'");
  expect_error({"lambda=1e9"}, "a number in [0.01, 100]");
  expect_error({"lambda=nan"}, "'lambda'");
  expect_error({"split=best"}, "one of: middle, median, sah");
  expect_error({"res=1,2"}, "three integers");
  expect_error({"bogus=1"},
               "unknown parameter 'bogus' for structure 'kdtree' (valid: leaf_size, lambda, split, res, flag)");
  expect_error({"leaf_size"}, "key=value");
}

TEST(Params, NumbersPrintShortestExact) {
  EXPECT_EQ(format_param_number(2.0), "2");
  EXPECT_EQ(format_param_number(0.2), "0.2");
  EXPECT_EQ(format_param_number(1000.0), "1000");
  EXPECT_EQ(format_param_number(double(0.1f)), "0.10000000149011612");
}

TEST(Registry, UnknownStructureListsValidNames) {
  auto s = find_structure("quadtree");
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("valid: brute"), std::string::npos) << s.error().message;
}

TEST(Registry, ParseStructureValidatesNameAndParametersTogether) {
  auto ok = parse_structure("kdtree", {"split=median"});
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_EQ(ok.value().info->name, "kdtree");
  EXPECT_EQ(ok.value().params.get_choice("split"), "median");
  auto bad_name = parse_structure("quadtree", {});
  ASSERT_FALSE(bad_name);
  EXPECT_EQ(bad_name.error().message, find_structure("quadtree").error().message);
  auto bad_param = parse_structure("kdtree", {"split=diagonal"});
  ASSERT_FALSE(bad_param);
  EXPECT_EQ(bad_param.error().message,
            ParamSet::parse(KdTree::param_specs(), {"split=diagonal"}, "kdtree").error().message);
}

TEST(Registry, EveryDefaultIsValidAndReadsBack) {
  for (const auto& info : structure_registry()) {
    for (const auto& spec : info.params) {
      EXPECT_TRUE(validate_param(spec, spec.default_typed)) << info.name << "." << spec.name;
      auto parsed = parse_param(spec, spec.default_value);
      ASSERT_TRUE(parsed) << info.name << "." << spec.name;
      EXPECT_EQ(parsed.value(), spec.default_typed) << info.name << "." << spec.name;
    }
  }
}

// The declarations bind to the structs the builders read: a parameter changes its field.
TEST(Registry, DeclarationsSetTheirFields) {
  auto grid = ParamSet::parse(UniformGrid::param_specs(), {"lambda=3.5", "insert=bbox", "mailbox=off", "res=2,3,4"});
  ASSERT_TRUE(grid);
  const UniformGridOptions g = UniformGrid::param_table().apply(grid.value());
  EXPECT_EQ(g.build.lambda, 3.5);
  EXPECT_EQ(g.build.insertion, GridInsertion::Bbox);
  EXPECT_FALSE(g.mailbox);
  EXPECT_EQ(g.build.res, (std::array<int, 3>{2, 3, 4}));

  auto kd = ParamSet::parse(KdTree::param_specs(), {"split=median", "clip=off", "empty_bonus=0.5"});
  ASSERT_TRUE(kd);
  const KdBuildOptions k = KdTree::param_table().apply(kd.value());
  EXPECT_EQ(k.split, KdSplit::Median);
  EXPECT_FALSE(k.clip);
  EXPECT_EQ(k.empty_bonus, 0.5);

  auto bvh = ParamSet::parse(bvh_param_specs(), {"builder=insertion", "traversal=pqueue", "width=2", "ct=0.5"});
  ASSERT_TRUE(bvh);
  const HierarchyOptions h = hierarchy_options(bvh.value());
  EXPECT_EQ(h.build.builder, BvhBuilderKind::Insertion);
  EXPECT_EQ(h.traversal, TraversalOrder::PriorityQueue);
  EXPECT_EQ(h.width, 2);
  EXPECT_EQ(h.build.ct, 0.5f);
}

TEST(Registry, EntriesCarryWhatFrontEndsNeed) {
  int hierarchies = 0;
  int references = 0, cell_structures = 0;
  for (const auto& info : structure_registry()) {
    EXPECT_FALSE(info.label.empty()) << info.name;
    EXPECT_FALSE(info.node_noun.empty()) << info.name;
    references += info.reference;
    cell_structures += info.cells;
    // A construction listing and a traversal listing of the same kind of structure.
    hierarchies += info.construction == ConstructionFamily::Hierarchy;
    EXPECT_EQ(info.construction == ConstructionFamily::Hierarchy, info.traversal == TraversalFamily::Hierarchy)
        << info.name;
    auto params = ParamSet::parse(info.params, {}, info.name);
    ASSERT_TRUE(params);
    EXPECT_EQ(info.create(params.value())->name(), info.name);
  }
  EXPECT_EQ(references, 1);
  EXPECT_EQ(cell_structures, 1);
  EXPECT_EQ(hierarchies, 2);
}

}  // namespace
}  // namespace accel
