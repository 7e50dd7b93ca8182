#include "memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace accel {
namespace {

/// The cgroup v2 limit of this process's group ("max" or absent = none), which containers
/// and CI runners set below the machine's memory.
size_t cgroup_memory_limit() {
  std::ifstream in("/sys/fs/cgroup/memory.max");
  std::string text;
  if (!(in >> text) || text == "max") return 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  return end && *end == '\0' ? size_t(v) : 0;
}

}  // namespace

size_t physical_memory_bytes() {
  static const size_t bytes = [] {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    size_t total = pages > 0 && page > 0 ? size_t(pages) * size_t(page) : size_t(4) << 30;
    const size_t group = cgroup_memory_limit();
    if (group > 0) total = std::min(total, group);
    return total;
  }();
  return bytes;
}

size_t default_memory_limit() { return size_t(double(physical_memory_bytes()) * kDefaultMemoryFraction); }

Result<size_t> parse_memory_size(const std::string& text, const std::string& what) {
  const auto bad = [&] {
    return make_error(what + " '" + text + "': expected a size such as 512M, 4G, 1.5GiB, a number of bytes or 25%");
  };
  size_t pos = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &pos);
  } catch (...) {
    return bad();
  }
  if (!std::isfinite(value) || value <= 0.0) return bad();
  std::string unit = text.substr(pos);
  for (char& c : unit) c = char(std::tolower(static_cast<unsigned char>(c)));
  double bytes = 0.0;
  if (unit == "%") {
    if (value > 100.0) return make_error(what + " '" + text + "': a share of physical memory is at most 100%");
    bytes = double(physical_memory_bytes()) * value / 100.0;
  } else {
    // Binary units whichever way they are spelt: memory is counted in pages, not in 1000s.
    static const std::pair<const char*, double> units[] = {
        {"", 1.0},           {"b", 1.0},           {"k", 0x1p10},  {"kb", 0x1p10}, {"kib", 0x1p10},
        {"m", 0x1p20},       {"mb", 0x1p20},       {"mib", 0x1p20}, {"g", 0x1p30}, {"gb", 0x1p30},
        {"gib", 0x1p30},     {"t", 0x1p40},        {"tb", 0x1p40},  {"tib", 0x1p40}};
    const auto* u = std::find_if(std::begin(units), std::end(units), [&](const auto& p) { return unit == p.first; });
    if (u == std::end(units)) return bad();
    bytes = value * u->second;
  }
  // Below a mebibyte no build of a real scene fits; above 2^60 the number is a typo.
  if (bytes < 0x1p20) return make_error(what + " '" + text + "': at least 1M");
  if (bytes > 0x1p60) return make_error(what + " '" + text + "': too large");
  return size_t(bytes);
}

std::string format_bytes(double bytes) {
  static const char* const names[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  int unit = 0;
  while (bytes >= 1024.0 && unit < 4) {
    bytes /= 1024.0;
    ++unit;
  }
  char out[48];
  if (unit == 0 || bytes >= 100.0 || bytes == std::floor(bytes))
    std::snprintf(out, sizeof out, "%.0f %s", bytes, names[unit]);
  else
    std::snprintf(out, sizeof out, "%.1f %s", bytes, names[unit]);
  return out;
}

std::string over_budget_text(double needed, size_t limit) {
  return "would need more than " + format_bytes(needed) + " (memory limit " + format_bytes(double(limit)) + ")";
}

}  // namespace accel
