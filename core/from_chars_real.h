#pragma once
// std::from_chars for float and double, where the standard library has it (libstdc++) and
// where it has not: emscripten 3.1.6's libc++ has only the integer overloads. There the same
// contract is kept on strtof / strtod, so the web page reads numbers exactly as the native
// build does: no leading blanks or '+', hex digits without "0x" in chars_format::hex,
// "inf" and "nan" accepted, result_out_of_range (value unchanged) when the number does not
// fit, strtod's correct rounding.
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <system_error>
#include <version>

namespace accel {

/// The strtof / strtod version (the tests compare it with std::from_chars natively).
template <class Real>
std::from_chars_result from_chars_by_strtod(const char* first, const char* last, Real& value,
                                            std::chars_format format = std::chars_format::general) {
  const std::from_chars_result invalid{first, std::errc::invalid_argument};
  if (first == last || std::isspace(static_cast<unsigned char>(*first)) || *first == '+') return invalid;
  // strtod reads "0x..." as hex in any mode; from_chars' general mode stops at the 'x'.
  std::string text(first, last);
  const size_t digits = text[0] == '-' ? 1 : 0;
  auto starts_with_word = [&](const char* word) {
    for (size_t i = 0; word[i]; ++i)
      if (digits + i >= text.size() || std::tolower(static_cast<unsigned char>(text[digits + i])) != word[i]) return false;
    return true;
  };
  const bool special = starts_with_word("inf") || starts_with_word("nan");
  size_t prefix = 0;
  if (format == std::chars_format::hex && !special) {
    text.insert(digits, "0x");
    prefix = 2;
  } else if (text.find_first_of("xX") != std::string::npos) {
    text.resize(text.find_first_of("xX"));  // as from_chars: the number ends before the 'x'
  }
  errno = 0;
  char* end = nullptr;
  const Real parsed = sizeof(Real) == sizeof(float) ? Real(std::strtof(text.c_str(), &end))
                                                    : Real(std::strtod(text.c_str(), &end));
  const size_t used = size_t(end - text.c_str());
  if (used <= prefix + digits) return invalid;
  const char* stop = first + (used - prefix);
  if (errno == ERANGE && (parsed == Real(0) || std::isinf(parsed))) return {stop, std::errc::result_out_of_range};
  value = parsed;
  return {stop, std::errc()};
}

template <class Real>
std::from_chars_result from_chars_real(const char* first, const char* last, Real& value,
                                       std::chars_format format = std::chars_format::general) {
#if defined(__cpp_lib_to_chars)
  return std::from_chars(first, last, value, format);
#else
  return from_chars_by_strtod(first, last, value, format);
#endif
}

}  // namespace accel
