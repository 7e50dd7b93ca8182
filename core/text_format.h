#pragma once
// Numbers as people read them in reports and panels.
#include <cstdint>
#include <cstdio>
#include <string>

namespace accel {

/// 25775 -> "25,775".
inline std::string with_separators(uint64_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

/// `v` through a printf format of one double: fixed(2.345, "%.1f") -> "2.3", "%.3g" for
/// three significant digits.
inline std::string fixed(double v, const char* format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

}  // namespace accel
