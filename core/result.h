#pragma once
// Result<T>: a value or a one-line error message; Status (= Result<void>): "it worked, or
// here is why not". Bad input (files, rays, parameters) is reported through them; the core
// never exits and never throws at its callers.
#include <string>
#include <string_view>
#include <utility>
#include <variant>

#include "check.h"

namespace accel {

/// A one-line, user-facing error: names the file and line, or the parameter, and the bad value.
struct Error {
  std::string message;
};

/// Either a T or an Error. Test with `ok()`, then take `value()` or `error()`.
template <class T>
class Result {
 public:
  Result(T value) : data_(std::move(value)) {}         // NOLINT: implicit on purpose
  Result(Error error) : data_(std::move(error)) {}     // NOLINT
  bool ok() const { return data_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() { ACCEL_CHECK(ok()); return std::get<0>(data_); }
  const T& value() const { ACCEL_CHECK(ok()); return std::get<0>(data_); }
  const Error& error() const { ACCEL_CHECK(!ok()); return std::get<1>(data_); }

 private:
  std::variant<T, Error> data_;
};

/// Success, or an Error: what an operation without a value returns.
template <>
class Result<void> {
 public:
  Result() = default;                                 ///< success
  Result(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit on purpose
  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const { ACCEL_CHECK(!ok_); return error_; }

 private:
  Error error_;
  bool ok_ = true;
};
using Status = Result<void>;

/// Builds an Error from a message.
inline Error make_error(std::string message) { return Error{std::move(message)}; }

/// A piece of the input as an error message quotes it: bytes outside printable ASCII as
/// \xNN and at most `max_chars` of them ("..." after), so binary garbage, terminal escapes,
/// a vertical tab or a 100 kB token keep the message one short line.
inline std::string printable(std::string_view text, size_t max_chars = 40) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    if (i == max_chars) return out + "...";
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

}  // namespace accel
