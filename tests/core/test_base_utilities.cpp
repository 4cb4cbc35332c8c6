// Direct tests of the base utilities the rest of the library leans on
// (issue 47, part 7): FastDivisor's exactness claim, number parsing,
// SlotStorage and the cache-size parser. Each was reached only through the
// code above it before.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "habuffer/cache_sizes.h"
#include "habuffer/fast_divisor.h"
#include "habuffer/number_text.h"
#include "habuffer/slot_storage.h"

namespace habuffer {
namespace {

// Divisors of every class the magic number's rounding treats differently:
// 1 (the wrapped magic), powers of two, their neighbours, odd primes,
// the largest values, and random ones.
std::vector<std::uint32_t> divisor_classes() {
  std::vector<std::uint32_t> d = {1, 2, 3, 5, 6, 7, 9, 10, 11, 13, 25, 100, 641, 1000, 6700417, 65535, 65537,
                                  0x7FFFFFFFu, 0x80000001u, 0xFFFFFFFEu, 0xFFFFFFFFu};
  for (int k = 1; k < 32; ++k) {
    const std::uint32_t p = 1u << k;
    d.insert(d.end(), {p, p - 1, p + 1});
  }
  std::mt19937 rng(7);
  for (int i = 0; i < 200; ++i) d.push_back(std::max<std::uint32_t>(1, static_cast<std::uint32_t>(rng())));
  return d;
}

// Dividends at every edge of a divisor: 0, around d and its multiples, and
// around 2^32 where the product with the magic is largest.
std::vector<std::uint32_t> edge_dividends(std::uint32_t d, std::mt19937& rng) {
  std::vector<std::uint32_t> v = {0, 1, 2, 0x7FFFFFFFu, 0x80000000u, 0xFFFFFFFEu, 0xFFFFFFFFu};
  const std::uint64_t top = std::uint64_t{0xFFFFFFFFu} / d * d;  // the largest multiple of d
  for (const std::uint64_t m : {std::uint64_t{d}, std::uint64_t{2} * d, top, top / 2 / d * d, std::uint64_t{1} << 31})
    for (const std::int64_t delta : {-1, 0, 1})
      if (const std::int64_t x = static_cast<std::int64_t>(m) + delta; x >= 0 && x <= 0xFFFFFFFFll)
        v.push_back(static_cast<std::uint32_t>(x));
  for (int i = 0; i < 64; ++i) v.push_back(static_cast<std::uint32_t>(rng()));
  return v;
}

TEST(FastDivisor, DivisionAndRemainderAreExactForEveryDivisorClassAtEveryEdgeDividend) {
  std::mt19937 rng(11);
  std::uint64_t checked = 0;
  for (const std::uint32_t d : divisor_classes()) {
    const FastDivisor f(d);
    ASSERT_EQ(f.divisor(), d);
    for (const std::uint32_t v : edge_dividends(d, rng)) {
      ASSERT_EQ(f.div(v), v / d) << v << " / " << d;
      ASSERT_EQ(f.mod(v), v % d) << v << " % " << d;
      ++checked;
    }
  }
  EXPECT_GT(checked, 20000u);
}

TEST(FastDivisor, EveryDividendIsExactForSmallDivisors) {
  // Exhaustive over a band of dividends for the divisors a small table uses.
  for (std::uint32_t d = 1; d <= 64; ++d) {
    const FastDivisor f(d);
    for (std::uint32_t v = 0; v < 100000; ++v) ASSERT_EQ(f.mod(v), v % d) << v << " % " << d;
    for (std::uint32_t v = 0xFFFFFFFFu - 100000; v != 0; ++v) ASSERT_EQ(f.div(v), v / d) << v << " / " << d;
  }
}

TEST(NumberText, UnsignedIntegersAreReadWholeWithinTheirRangeAndAnythingElseIsRefused) {
  EXPECT_EQ(parse_unsigned("0"), 0u);
  EXPECT_EQ(parse_unsigned("18446744073709551615"), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(parse_unsigned("42", 1, 42), 42u);
  for (const char* bad : {"", "-1", "+1", "1.0", "1e3", "12x", " 12", "0x10", "18446744073709551616", "nan"})
    EXPECT_THROW(parse_unsigned(bad), std::invalid_argument) << "'" << bad << "'";
  try {
    parse_unsigned("43", 1, 42);
    ADD_FAILURE() << "43 accepted in 1..42";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("43"), std::string::npos) << e.what();
  }
}

TEST(NumberText, Float32IsRoundedOnceAndTextThatCannotBeAFiniteFloat32IsRefused) {
  EXPECT_EQ(parse_float32("0.1"), 0.1f);
  EXPECT_EQ(parse_float32("16777217"), 16777216.0f);  // rounded once, to nearest even
  EXPECT_EQ(parse_float32("3.4028235e38"), std::numeric_limits<float>::max());
  EXPECT_EQ(parse_float32("0"), 0.0f);
  for (const char* bad : {"1e39", "1e-50", "nan", "inf", "-inf", "", "1.5x", "0.5 "})
    EXPECT_THROW(parse_float32(bad), std::invalid_argument) << "'" << bad << "'";
  EXPECT_EQ(parse_float64("1e300"), 1e300);
  EXPECT_THROW(parse_float64("1e400"), std::invalid_argument);
}

TEST(NumberText, TheShortestTextReadsBackAsTheSameValue) {
  std::mt19937 rng(3);
  std::vector<float> values = {0.0f, 0.1f, 1.0f / 3.0f, std::numeric_limits<float>::min(),
                               std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::max(), -2.5f};
  for (int i = 0; i < 1000; ++i) values.push_back(std::ldexp(static_cast<float>(rng()) / 4294967296.0f, static_cast<int>(rng() % 200) - 100));
  for (const float v : values) {
    const std::string t = shortest_text(v);
    EXPECT_EQ(std::strtof(t.c_str(), nullptr), v) << t;
    EXPECT_LE(t.size(), 15u) << t;
  }
  EXPECT_EQ(shortest_text(0.1f), "0.1");
  for (const double v : {0.1, 1.0 / 3.0, 1e300, 5e-324}) EXPECT_EQ(std::strtod(shortest_text(v).c_str(), nullptr), v);
}

TEST(SlotStorage, SlotsStartZeroAreCountedClearedAndMovedWithTheirOwnership) {
  SlotStorage<std::uint64_t> t(1000);
  ASSERT_EQ(t.size(), 1000u);
  EXPECT_EQ(t.bytes(), 8000u);
  EXPECT_EQ(t.count_nonempty(), 0u);
  for (std::uint64_t i = 0; i < 1000; i += 3) t.data()[i] = i + 1;
  EXPECT_EQ(t.count_nonempty(), 334u);
  SlotStorage<std::uint64_t> moved(std::move(t));
  EXPECT_EQ(t.size(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is the contract
  EXPECT_EQ(t.data(), nullptr);
  EXPECT_EQ(moved.slots()[999], 1000u);
  EXPECT_EQ(moved.clear_and_count(), 334u);
  EXPECT_EQ(moved.count_nonempty(), 0u);
  SlotStorage<std::uint32_t> narrow(5);
  EXPECT_EQ(narrow.bytes(), 20u);
  narrow.data()[4] = 7;
  narrow.clear();
  EXPECT_EQ(narrow.count_nonempty(), 0u);
  EXPECT_THROW(SlotStorage<std::uint64_t>(std::uint64_t{1} << 46), std::length_error) << "2^49 bytes";
  const SlotStorage<std::uint64_t> none;
  EXPECT_EQ(none.size(), 0u);
  EXPECT_EQ(none.data(), nullptr);
}

TEST(CacheSizes, SysfsSizesAreParsedInTheirUnitsAndAnythingElseIsZero) {
  EXPECT_EQ(parse_cache_size("512K"), 512u * 1024);
  EXPECT_EQ(parse_cache_size("32768K"), 32768u * 1024);
  EXPECT_EQ(parse_cache_size("2M"), 2u << 20);
  EXPECT_EQ(parse_cache_size("1048576"), 1048576u);
  EXPECT_EQ(parse_cache_size("1G"), std::uint64_t{1} << 30);
  for (const char* bad : {"", "K", "12X", "-1K", "abc", "12KB", "99999999999999999999"}) EXPECT_EQ(parse_cache_size(bad), 0u) << "'" << bad << "'";
  const CacheSizes& c = cache_sizes();
  EXPECT_GT(c.l2, 0u) << "the L2 is never 0 (the default where the system says nothing)";
  EXPECT_FALSE(c.source.empty());
}

}  // namespace
}  // namespace habuffer
