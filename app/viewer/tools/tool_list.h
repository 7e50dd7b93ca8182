#pragma once
// The viewer's tools, in the order App calls them (tools/tool.h).
#include <memory>
#include <vector>

#include "tools/tool.h"

namespace viz {

/// One of each tool, in App's order: keys are offered, sections listed, panels placed and
/// drawing layered in this order.
std::vector<std::unique_ptr<Tool>> make_tools();

}  // namespace viz
