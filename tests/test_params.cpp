// Parameter validation: the CLI's error messages name the parameter and its range.
#include <gtest/gtest.h>

#include "params.h"
#include "registry.h"

namespace accel {
namespace {

std::vector<ParamSpec> specs() {
  return {{"leaf_size", ParamSpec::Type::Int, "4", 1, 64, {}, "max triangles per leaf"},
          {"lambda", ParamSpec::Type::Float, "1", 0.01, 100, {}, "cells per cbrt(N)"},
          {"split", ParamSpec::Type::Choice, "sah", 0, 0, {"middle", "median", "sah"}, "split rule"},
          {"res", ParamSpec::Type::Int3, "8,8,8", 1, 1024, {}, "grid resolution"}};
}

TEST(Params, DefaultsAndOverrides) {
  auto p = ParamSet::parse(specs(), {"leaf_size=8", "res=4,5,6"}, "kdtree");
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p.value().get_int("leaf_size"), 8);
  EXPECT_DOUBLE_EQ(p.value().get_float("lambda"), 1.0);
  EXPECT_EQ(p.value().get_choice("split"), "sah");
  EXPECT_EQ(p.value().get_int3("res"), (std::array<int, 3>{4, 5, 6}));
  EXPECT_TRUE(p.value().is_set("leaf_size"));
  EXPECT_FALSE(p.value().is_set("lambda"));
  EXPECT_EQ(p.value().to_string(), "leaf_size=8,res=4,5,6");
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
  expect_error({"bogus=1"}, "unknown parameter 'bogus' for structure 'kdtree' (valid: leaf_size, lambda, split, res)");
  expect_error({"leaf_size"}, "key=value");
}

TEST(Registry, UnknownStructureListsValidNames) {
  auto s = find_structure("quadtree");
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("valid: brute"), std::string::npos) << s.error().message;
}

TEST(Registry, EveryDefaultIsValid) {
  for (const auto& info : structure_registry()) {
    for (const auto& spec : info.params) EXPECT_TRUE(validate_param(spec, spec.default_value)) << info.name << "." << spec.name;
  }
}

}  // namespace
}  // namespace accel
