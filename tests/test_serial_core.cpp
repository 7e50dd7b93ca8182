// The web build's core without threads, checked natively: par:: (parallel.h) compiled with
// ACCEL_WITH_TBB=0 keeps TBB's contract as the builders use it, and from_chars_by_strtod
// (the web's float parsing, from_chars_real.h) reads every number std::from_chars reads the
// same way. This unit is its own executable: the macro would change parallel.h for the rest.
#define ACCEL_WITH_TBB 0
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "from_chars_real.h"
#include "parallel.h"

namespace accel {
namespace {

TEST(SerialParallel, ForHandsOutPiecesOfAtMostTheGrainInOrder) {
  std::vector<std::pair<size_t, size_t>> pieces;
  par::parallel_for(par::blocked_range<size_t>(3, 1000, 64),
                    [&](const par::blocked_range<size_t>& r) { pieces.emplace_back(r.begin(), r.end()); });
  ASSERT_FALSE(pieces.empty());
  EXPECT_EQ(pieces.front().first, 3u);
  EXPECT_EQ(pieces.back().second, 1000u);
  for (size_t i = 0; i < pieces.size(); ++i) {
    EXPECT_LE(pieces[i].second - pieces[i].first, 64u);
    EXPECT_LT(pieces[i].first, pieces[i].second);
    if (i > 0) {
      EXPECT_EQ(pieces[i].first, pieces[i - 1].second);
    }
  }
  std::vector<int> order;
  par::parallel_for(0, 5, [&](int i) { order.push_back(i); });
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
  par::parallel_for(par::blocked_range<int>(7, 7, 4), [&](const par::blocked_range<int>&) { ADD_FAILURE(); });
}

TEST(SerialParallel, ReduceFoldsPiecesInOrderAndInvokeRunsLeftToRight) {
  // A non-commutative fold shows the order: the digits in sequence.
  const std::string digits = par::parallel_reduce(
      par::blocked_range<int>(0, 10, 3), std::string(),
      [](const par::blocked_range<int>& r, std::string acc) {
        for (int i = r.begin(); i < r.end(); ++i) acc += char('0' + i);
        return acc;
      },
      [](const std::string& a, const std::string& b) { return a + b; });
  EXPECT_EQ(digits, "0123456789");
  std::string calls;
  par::parallel_invoke([&] { calls += 'a'; }, [&] { calls += 'b'; }, [&] { calls += 'c'; });
  EXPECT_EQ(calls, "abc");
  uint32_t x = 5;
  EXPECT_EQ(par::fetch_add(x, uint32_t(3)), 5u);
  EXPECT_EQ(x, 8u);
  par::enumerable_thread_specific<int> local;
  local.local() = 4;
  int sum = 0;
  for (int v : local) sum += v;
  EXPECT_EQ(sum, 4);
  EXPECT_EQ(par::task_arena(1).execute([] { return 42; }), 42);
}

// Both parsers on one token: the same success, stop, error and value (bit for bit).
template <class Real>
void expect_same(const std::string& token, std::chars_format format) {
  Real a = Real(-7), b = Real(-7);
  const auto ra = std::from_chars(token.data(), token.data() + token.size(), a, format);
  const auto rb = from_chars_by_strtod(token.data(), token.data() + token.size(), b, format);
  SCOPED_TRACE("token '" + token + "'" + (format == std::chars_format::hex ? " (hex)" : ""));
  EXPECT_EQ(int(ra.ec), int(rb.ec));
  if (ra.ec == std::errc() || ra.ec == std::errc::result_out_of_range) {
    EXPECT_EQ(ra.ptr - token.data(), rb.ptr - token.data());
  }
  if (ra.ec == std::errc()) {
    EXPECT_EQ(std::isnan(a), std::isnan(b));
    EXPECT_EQ(std::signbit(a), std::signbit(b)) << a << " vs " << b;
    if (!std::isnan(a)) {
      EXPECT_EQ(a, b);
    }
  }
}

TEST(FromCharsByStrtod, ReadsWhatFromCharsReads) {
  const std::vector<std::string> general = {
      "0", "-0", "1", "-1.5", "3.25e2", "1e-3", ".5", "5.", "1e", "1e+", "e5", "+1", " 1", "1 ", "",
      "-", "inf", "-inf", "Infinity", "nan", "-nan", "nan(123)", "0x1p3", "1x", "1.2.3", "00012",
      "1e400", "-1e400", "1e-400", "3.4028236e38", "1.17549435e-38", "1.4e-45", "2.5e-46", "0.1",
      "123456789012345678901234567890", "7.0e-310", "abc", "--1", "1e5000", "0.0000001", "1,5"};
  for (const std::string& t : general) {
    expect_same<float>(t, std::chars_format::general);
    expect_same<double>(t, std::chars_format::general);
  }
  const std::vector<std::string> hex = {"1p3", "1.8p+3", "-1.8p-2", "0", "ff", "1p", "p3", "inf", "nan",
                                        "0x1p3", "1.fffffep127", "1p200", "1p-160", "g"};
  for (const std::string& t : hex) expect_same<float>(t, std::chars_format::hex);
  // Round trips of random values, as rays files and OBJ files write them.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> exponent(-40.0, 38.0), mantissa(-1.0, 1.0);
  char text[64];
  for (int i = 0; i < 20000; ++i) {
    const double v = mantissa(rng) * std::pow(10.0, exponent(rng));
    std::snprintf(text, sizeof text, "%.9g", v);
    expect_same<float>(text, std::chars_format::general);
    std::snprintf(text, sizeof text, "%.17g", v);
    expect_same<double>(text, std::chars_format::general);
    std::snprintf(text, sizeof text, "%a", double(float(v)));
    const std::string h(text);
    const size_t x = h.find("0x");
    expect_same<float>(h.substr(0, x) + h.substr(x + 2), std::chars_format::hex);
  }
}

}  // namespace
}  // namespace accel
