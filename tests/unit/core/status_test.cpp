// SPDX-License-Identifier: MIT
#include "rewind/core/status.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace rwd {
namespace {

TEST(Result, HoldsAValueOrTheErrorWhyNot) {
  Result<int> seven = 7;
  ASSERT_TRUE(seven.ok());
  EXPECT_EQ(*seven, 7);
  EXPECT_EQ(seven.value(), 7);
  Result<int> none = Status::Error(ErrorCode::kNotFound, "no such body");
  EXPECT_FALSE(none.ok());
  EXPECT_EQ(none.status().code(), ErrorCode::kNotFound);
}

TEST(Result, ReadingAFailedResultThrowsWithItsMessage) {
  Result<std::unique_ptr<int>> none = Status::Error(ErrorCode::kInvalidArgument, "radius < 0");
  // Every way in is checked: value(), *, -> (const and not).
  EXPECT_THROW((void)none.value(), BadResultAccess);
  EXPECT_THROW((void)*none, BadResultAccess);
  EXPECT_THROW((void)none->get(), BadResultAccess);
  const Result<std::unique_ptr<int>>& view = none;
  EXPECT_THROW((void)view.value(), BadResultAccess);
  EXPECT_THROW((void)*view, BadResultAccess);
  try {
    (void)none.value();
  } catch (const BadResultAccess& e) {
    EXPECT_NE(std::string(e.what()).find("radius < 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rwd
