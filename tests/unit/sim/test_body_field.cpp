// SPDX-License-Identifier: MIT
#include "rewind/core/body_field.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace rwd::sim {
namespace {

TEST(BodyField, ValuesReadBackExactly) {
  EXPECT_EQ(BodyField::float32(0, "f", -2.5f).value(), -2.5);
  EXPECT_EQ(BodyField::unsigned_int(0, "u", uint64_t{1} << 40).value(), 1099511627776.0);
  EXPECT_EQ(BodyField::signed_int(0, "s", -12345).value(), -12345.0);
  EXPECT_EQ(BodyField::fixed16(0, "q", -(3 << 16) - (1 << 15)).value(), -3.5);
  EXPECT_EQ(BodyField::fixed16(0, "q", 1).value(), 1.0 / 65536.0);
}

TEST(BodyField, DiffComparesBitsAndType) {
  const std::vector<BodyField> a = {BodyField::fixed16(2, "position.x", 65536),
                                    BodyField::signed_int(2, "turns", -1)};
  std::vector<BodyField> b = a;
  EXPECT_TRUE(diff_body_fields(a, b).empty());
  b[0] = BodyField::fixed16(2, "position.x", 65537);
  b[1] = BodyField::unsigned_int(2, "turns", static_cast<uint64_t>(-1));
  const auto diff = diff_body_fields(a, b);
  ASSERT_EQ(diff.size(), 2u);
  EXPECT_EQ(diff[0].body_index, 2u);
  EXPECT_EQ(diff[0].field, "position.x");
  EXPECT_EQ(diff[0].expected, 1.0);
  EXPECT_EQ(diff[0].actual, 65537.0 / 65536.0);
  EXPECT_EQ(diff[1].field, "turns");
}

TEST(BodyField, DiffReportsFieldsOnOneSideOnly) {
  const std::vector<BodyField> expected = {BodyField::unsigned_int(1, "kind", 2),
                                           BodyField::float32(1, "position.z", 4.0f)};
  const std::vector<BodyField> actual = {BodyField::unsigned_int(1, "kind", 2),
                                         BodyField::fixed16(1, "angle", 1 << 16)};
  const auto diff = diff_body_fields(expected, actual);
  ASSERT_EQ(diff.size(), 2u);
  EXPECT_EQ(diff[0].field, "position.z");
  EXPECT_EQ(diff[0].expected, 4.0);
  EXPECT_EQ(diff[0].actual, 0.0);
  EXPECT_EQ(diff[1].field, "angle");
  EXPECT_EQ(diff[1].expected, 0.0);
  EXPECT_EQ(diff[1].actual, 1.0);
}

}  // namespace
}  // namespace rwd::sim
