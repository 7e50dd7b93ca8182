#pragma once
// The builders' stable sort of millions of items by an integer key (the sweep builder's
// centres, the kd-tree's root events): an LSD radix sort, a pass per digit.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace accel {

/// Sorts `items` stably by key(item), an unsigned integer of at most `KeyBits` bits, in
/// passes of `DigitBits` bits from the lowest; a digit every item shares is skipped (a
/// scene's high position bits often are). `scratch` is a buffer; it ends the size of `items`.
template <int KeyBits, int DigitBits, class T, class KeyOf>
void radix_sort_stable(std::vector<T>& items, std::vector<T>& scratch, KeyOf key) {
  constexpr uint64_t kDigitMask = (uint64_t(1) << DigitBits) - 1;
  scratch.resize(items.size());
  for (int shift = 0; shift < KeyBits; shift += DigitBits) {
    std::array<size_t, kDigitMask + 1> start{};
    for (const T& v : items) ++start[(uint64_t(key(v)) >> shift) & kDigitMask];
    if (std::find(start.begin(), start.end(), items.size()) != start.end()) continue;  // one bucket holds them all
    size_t sum = 0;
    for (size_t& s : start) sum += std::exchange(s, sum);
    for (const T& v : items) scratch[start[(uint64_t(key(v)) >> shift) & kDigitMask]++] = v;
    items.swap(scratch);
  }
}

}  // namespace accel
