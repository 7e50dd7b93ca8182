#pragma once
// accel::bit_cast: std::bit_cast, which emscripten 3.1.6's libc++ (the web build) lacks; the
// compiler's builtin is what std::bit_cast is made of in both standard libraries.
#include <type_traits>

namespace accel {

template <class To, class From>
constexpr To bit_cast(const From& from) noexcept {
  static_assert(sizeof(To) == sizeof(From) && std::is_trivially_copyable_v<To> && std::is_trivially_copyable_v<From>);
  return __builtin_bit_cast(To, from);
}

}  // namespace accel
