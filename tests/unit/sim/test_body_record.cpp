// SPDX-License-Identifier: MIT
#include "rewind/sim/body_record.h"

#include <gtest/gtest.h>

namespace rwd::sim {
namespace {

BodyRecord make(uint32_t index) {
  BodyRecord r;
  r.id = {index, 1};
  r.position = {1.0f, 2.0f, 3.0f};
  return r;
}

std::vector<BodyField> fields_of(const std::vector<BodyRecord>& records) {
  std::vector<BodyField> out;
  for (const BodyRecord& r : records) append_body_fields(r, out);
  return out;
}

TEST(BodyRecord, FieldsKeepOrderAndExactValues) {
  BodyRecord r = make(4);
  r.user_data = 77;
  r.rotation = {0.0f, 0.6f, 0.0f, 0.8f};
  r.awake = false;
  std::vector<BodyField> fields;
  append_body_fields(r, fields);
  ASSERT_EQ(fields.size(), 18u);
  const char* names[] = {"generation",
                         "kind",
                         "user_data",
                         "position.x",
                         "position.y",
                         "position.z",
                         "rotation.x",
                         "rotation.y",
                         "rotation.z",
                         "rotation.w",
                         "linear_velocity.x",
                         "linear_velocity.y",
                         "linear_velocity.z",
                         "angular_velocity.x",
                         "angular_velocity.y",
                         "angular_velocity.z",
                         "awake",
                         "enabled"};
  for (size_t k = 0; k < fields.size(); ++k) {
    EXPECT_EQ(fields[k].body_index, 4u);
    EXPECT_EQ(fields[k].name, names[k]);
  }
  EXPECT_EQ(fields[2].value(), 77.0);
  EXPECT_EQ(fields[4].type, FieldType::kFloat32);
  EXPECT_EQ(fields[4].value(), 2.0);
  EXPECT_EQ(fields[7].value(), static_cast<double>(0.6f));
  EXPECT_EQ(fields[16].value(), 0.0);
  EXPECT_EQ(fields[17].value(), 1.0);
}

TEST(BodyRecord, DiffNamesEveryDifferingField) {
  std::vector<BodyRecord> expected = {make(0), make(1), make(3)};
  std::vector<BodyRecord> actual = {make(0), make(1), make(2)};
  actual[0].position.x = 1.5f;
  actual[1].rotation.w = 0.5f;
  actual[1].linear_velocity.z = -1.0f;
  auto diff = diff_body_fields(fields_of(expected), fields_of(actual));
  ASSERT_EQ(diff.size(), 5u);
  EXPECT_EQ(diff[0].body_index, 0u);
  EXPECT_EQ(diff[0].field, "position.x");
  EXPECT_EQ(diff[0].expected, 1.0);
  EXPECT_EQ(diff[0].actual, 1.5);
  EXPECT_EQ(diff[1].field, "rotation.w");
  EXPECT_EQ(diff[2].field, "linear_velocity.z");
  EXPECT_EQ(diff[3].body_index, 2u);
  EXPECT_EQ(diff[3].field, "exists");
  EXPECT_EQ(diff[3].expected, 0.0);
  EXPECT_EQ(diff[4].body_index, 3u);
  EXPECT_EQ(diff[4].field, "exists");
  EXPECT_EQ(diff[4].expected, 1.0);
}

TEST(BodyRecord, DiffIsBitExact) {
  std::vector<BodyRecord> a = {make(0)};
  std::vector<BodyRecord> b = a;
  EXPECT_TRUE(diff_body_fields(fields_of(a), fields_of(b)).empty());
  b[0].angular_velocity.y = -0.0f;  // equal by ==, different bits
  auto diff = diff_body_fields(fields_of(a), fields_of(b));
  ASSERT_EQ(diff.size(), 1u);
  EXPECT_EQ(diff[0].field, "angular_velocity.y");
}

}  // namespace
}  // namespace rwd::sim
