// SPEC 2: records, depth codes, ordering.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "habuffer/record_layout.h"

namespace habuffer {
namespace {

TEST(RecordLayout, RejectsAgeBitsOutsideFourToTwelve) {
  EXPECT_THROW(RecordLayout(Layout::L64, 3), std::invalid_argument);
  EXPECT_THROW(RecordLayout(Layout::L32, 13), std::invalid_argument);
  EXPECT_NO_THROW(RecordLayout(Layout::L64, 4));
  EXPECT_NO_THROW(RecordLayout(Layout::L32, 12));
}

TEST(RecordLayout, PackUnpackRoundTripsAtEveryAgeBitsAndTheFieldLimits) {
  for (Layout layout : {Layout::L64, Layout::L32})
    for (std::uint32_t bits = 4; bits <= 12; ++bits) {
      const RecordLayout l(layout, bits);
      EXPECT_EQ(l.max_age(), (1u << bits) - 1);
      EXPECT_EQ(l.max_code(), (1u << (32 - bits)) - 1);
      for (std::uint32_t age : {1u, 2u, l.max_age()})
        for (std::uint32_t code : {0u, 1u, l.max_code() / 2, l.max_code()})
          for (std::uint32_t data : {0u, 0xDEADBEEFu, 0xFFFFFFFFu}) {
            const std::uint64_t r = l.pack(age, code, data);
            EXPECT_EQ(l.age(r), age);
            EXPECT_EQ(l.code(r), code);
            EXPECT_EQ(l.data(r), layout == Layout::L64 ? data : 0u);
            EXPECT_NE(r, 0u) << "stored records are never the empty value";
            if (layout == Layout::L32) {
              EXPECT_LE(r, 0xFFFFFFFFull);
            }
            const std::uint64_t older = l.with_age(r, age == l.max_age() ? 1 : age + 1);
            EXPECT_EQ(l.code(older), code);
            EXPECT_EQ(l.data(older), l.data(r));
          }
    }
}

TEST(RecordLayout, RecordsCompareByAgeThenDepthCodeThenData) {
  const RecordLayout l(Layout::L64, 8);
  EXPECT_GT(l.pack(2, 0, 0), l.pack(1, l.max_code(), 0xFFFFFFFFu));
  EXPECT_GT(l.pack(1, 5, 0), l.pack(1, 4, 0xFFFFFFFFu));
  EXPECT_GT(l.pack(1, 5, 2), l.pack(1, 5, 1));
}

TEST(RecordLayout, DepthCodeIsReversedSoNearerIsLarger) {
  for (std::uint32_t bits : {4u, 8u, 12u}) {
    const RecordLayout l(Layout::L64, bits);
    EXPECT_EQ(l.depth_code(0.0f), l.max_code());
    EXPECT_EQ(l.depth_code(-0.0f), l.max_code());
    EXPECT_EQ(l.depth_code(1.0f), 0u);  // floor(2^D) clamps to 2^D - 1
    EXPECT_EQ(l.depth_code(0.5f), l.max_code() - (1u << (31 - bits)));
    EXPECT_GT(l.depth_code(0.25f), l.depth_code(0.75f));
    // The largest float below 1: its code is nonzero only where D > 24 bits
    // can tell it from 1 (float32 has 24 bits of precision).
    const float below_one = std::nextafter(1.0f, 0.0f);
    EXPECT_EQ(l.depth_code(below_one), bits < 8 ? (1u << (8 - bits)) - 1 : 0u);
  }
}

TEST(RecordLayout, DepthCodeIsExactFloorOfScaledFloat) {
  const RecordLayout l(Layout::L64, 8);  // D = 24: every float step is visible near 0
  const float t = 0.1f;
  const auto expected = l.max_code() - static_cast<std::uint32_t>(std::floor(static_cast<double>(t) * (1 << 24)));
  EXPECT_EQ(l.depth_code(t), expected);
}

TEST(RecordLayout, NanAndOutOfRangeDepthsAreInvalidNeverClamped) {
  EXPECT_FALSE(RecordLayout::depth_valid(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_FALSE(RecordLayout::depth_valid(-std::numeric_limits<float>::quiet_NaN()));
  EXPECT_FALSE(RecordLayout::depth_valid(std::numeric_limits<float>::infinity()));
  EXPECT_FALSE(RecordLayout::depth_valid(-std::numeric_limits<float>::infinity()));
  EXPECT_FALSE(RecordLayout::depth_valid(std::nextafter(1.0f, 2.0f)));
  EXPECT_FALSE(RecordLayout::depth_valid(-std::numeric_limits<float>::denorm_min()));
  EXPECT_TRUE(RecordLayout::depth_valid(0.0f));
  EXPECT_TRUE(RecordLayout::depth_valid(-0.0f));
  EXPECT_TRUE(RecordLayout::depth_valid(1.0f));
  EXPECT_TRUE(RecordLayout::depth_valid(std::numeric_limits<float>::denorm_min()));
}

}  // namespace
}  // namespace habuffer
