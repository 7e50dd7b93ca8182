#pragma once
// The suite every structure x option runs: identical answers to the reference (docs/hits.md
// rule) on procedural scenes, small shared meshes (when present) and edge-case scenes, and
// recording that never changes the answer. A structure's test file instantiates it with its
// configurations:
//
//   INSTANTIATE_TEST_SUITE_P(Grid, StructureVsReference,
//       ::testing::Values(SuiteCase{"grid", {}}, SuiteCase{"grid", {"mailbox=on"}}), suite_case_name);
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace accel::testing {

/// One structure configuration: registry name and `key=value` parameters.
struct SuiteCase {
  std::string structure;
  std::vector<std::string> params;
};

/// gtest-safe name, e.g. "grid_mailbox_on".
std::string suite_case_name(const ::testing::TestParamInfo<SuiteCase>& info);

class StructureVsReference : public ::testing::TestWithParam<SuiteCase> {};

}  // namespace accel::testing
