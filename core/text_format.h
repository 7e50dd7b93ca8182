#pragma once
// Numbers as people read them in reports and panels.
#include <cstdint>
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

}  // namespace accel
