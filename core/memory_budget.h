#pragma once
// The memory budget of a build: one byte limit that every builder checks what it allocates
// against, so an explosive parameter set (a deep octree over overlapping triangles, a
// kd-tree whose references multiply by straddling, a fine grid over long slivers) stops
// with a one-line error naming the parameter to lower instead of being killed by the
// system. The limit travels with the BuildControl (build_control.h); without one, or with
// none set, it is kDefaultMemoryFraction of the machine's physical memory.
#include <cstddef>
#include <string>

#include "result.h"

namespace accel {

/// The default budget's share of physical memory: half, which leaves the other half to the
/// scene, the traced rays and whatever else runs beside the build.
inline constexpr double kDefaultMemoryFraction = 0.5;

/// Physical memory of this machine (or of the cgroup it runs in, when that is smaller).
size_t physical_memory_bytes();
/// kDefaultMemoryFraction of physical_memory_bytes().
size_t default_memory_limit();

/// Parses a memory size as the CLI takes it: "4G", "512M", "1.5GiB", "64k", a plain number
/// of bytes, or "25%" of physical memory. Errors name `what` (e.g. "--memory-limit").
Result<size_t> parse_memory_size(const std::string& text, const std::string& what = "memory limit");
/// "512 MiB", "1.5 GiB", "800 B": for error messages and the viewer.
std::string format_bytes(double bytes);

/// The clause every over-budget error ends its first part with, e.g.
/// "would need about 6.1 GiB (memory limit 4 GiB)". `needed` is a lower bound when the
/// build stopped on its way there.
std::string over_budget_text(double needed, size_t limit);

}  // namespace accel
