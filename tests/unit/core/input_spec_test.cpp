// SPDX-License-Identifier: MIT
// A game's input: the bytes of its struct, a spec that names and bounds the
// fields, checks of both, and the helpers tools use (describe, random,
// predict).
#include "rewind/core/input_spec.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "rewind/core/stick_input.h"

namespace rwd {
namespace {

struct CarInput {
  int16_t steer = 0;     // [-500, 500]
  uint8_t throttle = 0;  // [0, 100]
  uint8_t brake = 0;     // [0, 1]
  int32_t horn = 0;      // [-1, 70000]
};
static_assert(InputLayout<CarInput> && sizeof(CarInput) == 8);

PlayerInput release_brake(const PlayerInput& newest) {
  CarInput car = newest.as<CarInput>();
  car.brake = 0;
  return PlayerInput::of(car);
}

constexpr InputField kCarFields[] = {
    {"steer", InputFieldType::kI16, offsetof(CarInput, steer), -500, 500},
    {"throttle", InputFieldType::kU8, offsetof(CarInput, throttle), 0, 100},
    {"brake", InputFieldType::kU8, offsetof(CarInput, brake), 0, 1},
    {"horn", InputFieldType::kI32, offsetof(CarInput, horn), -1, 70000},
};
constexpr InputSpec kCarSpec{"car", sizeof(CarInput), kCarFields, &release_brake};

// Types the concept refuses: padding, floating point, too big.
struct Padded {
  uint8_t a;
  uint32_t b;
};
struct Floaty {
  float x;
};
struct Huge {
  uint8_t bytes[kInputCapacity + 1];
};
static_assert(!InputLayout<Padded>);
static_assert(!InputLayout<Floaty>);
static_assert(!InputLayout<Huge>);

TEST(InputSpec, AStructRoundTripsThroughItsBytes) {
  const CarInput car{-321, 77, 1, 65536};
  const PlayerInput input = PlayerInput::of(car);
  const CarInput back = input.as<CarInput>();
  EXPECT_EQ(back.steer, -321);
  EXPECT_EQ(back.throttle, 77);
  EXPECT_EQ(back.brake, 1);
  EXPECT_EQ(back.horn, 65536);
  for (size_t b = sizeof(CarInput); b < kInputCapacity; ++b) EXPECT_EQ(input.bytes[b], 0) << b;
  EXPECT_TRUE(PlayerInput{}.is_neutral());
  EXPECT_FALSE(input.is_neutral());
  // Little-endian, field by field, as the wire and the replays carry it.
  EXPECT_EQ(input.bytes[0], 0xBF);  // -321 = 0xFEBF
  EXPECT_EQ(input.bytes[1], 0xFE);
}

TEST(InputSpec, FieldsReadAndWriteWithTheirSign) {
  PlayerInput input = PlayerInput::of(CarInput{-500, 100, 0, -1});
  EXPECT_EQ(read_input_field(input, kCarFields[0]), -500);
  EXPECT_EQ(read_input_field(input, kCarFields[1]), 100);
  EXPECT_EQ(read_input_field(input, kCarFields[3]), -1);
  write_input_field(input, kCarFields[0], 499);
  write_input_field(input, kCarFields[3], 70000);
  EXPECT_EQ(input.as<CarInput>().steer, 499);
  EXPECT_EQ(input.as<CarInput>().horn, 70000);
  const InputField wide{"w", InputFieldType::kU32, 0, 0, UINT32_MAX};
  PlayerInput all;
  write_input_field(all, wide, UINT32_MAX);
  EXPECT_EQ(read_input_field(all, wide), int64_t{UINT32_MAX});
}

TEST(InputSpec, CheckInputNamesTheFieldOrTheByte) {
  EXPECT_TRUE(check_input(kCarSpec, PlayerInput{}).ok());
  EXPECT_TRUE(check_input(kCarSpec, PlayerInput::of(CarInput{500, 100, 1, 70000})).ok());
  Status s = check_input(kCarSpec, PlayerInput::of(CarInput{501, 0, 0, 0}));
  EXPECT_EQ(s.code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "input field 'steer' is 501, outside [-500, 500]");
  s = check_input(kCarSpec, PlayerInput::of(CarInput{0, 0, 2, 0}));
  EXPECT_EQ(s.message(), "input field 'brake' is 2, outside [0, 1]");
  PlayerInput past;
  past.bytes[8] = 1;
  s = check_input(kCarSpec, past);
  EXPECT_EQ(s.message(), "input byte 8 is set, past the game's 8-byte input");
}

TEST(InputSpec, BadSpecsAreRefusedWithTheReason) {
  EXPECT_TRUE(check_input_spec(kCarSpec).ok());
  EXPECT_TRUE(check_input_spec(stick_input_spec()).ok());
  auto message = [](const InputSpec& spec) { return check_input_spec(spec).message(); };
  EXPECT_EQ(message({"x", 0, {}, nullptr}), "an input spec's size must be 1 to 32 bytes, not 0");
  EXPECT_EQ(message({"x", 33, {}, nullptr}), "an input spec's size must be 1 to 32 bytes, not 33");
  const InputField past[] = {{"a", InputFieldType::kI32, 6, 0, 1}};
  EXPECT_EQ(message({"x", 8, past, nullptr}), "input field 0 ('a'): ends past the input's 8 bytes");
  const InputField overlap[] = {{"a", InputFieldType::kI16, 0, 0, 1},
                                {"b", InputFieldType::kU8, 1, 0, 1}};
  EXPECT_EQ(message({"x", 8, overlap, nullptr}), "input field 1 ('b'): overlaps another field");
  const InputField twice[] = {{"a", InputFieldType::kU8, 0, 0, 1},
                              {"a", InputFieldType::kU8, 1, 0, 1}};
  EXPECT_EQ(message({"x", 8, twice, nullptr}), "input field 1 ('a'): the name is used twice");
  const InputField unnamed[] = {{"", InputFieldType::kU8, 0, 0, 1}};
  EXPECT_NE(message({"x", 8, unnamed, nullptr}).find("a name is 1 to 32"), std::string::npos);
  const InputField spaced[] = {{"two words", InputFieldType::kU8, 0, 0, 1}};
  EXPECT_NE(message({"x", 8, spaced, nullptr}).find("a name is 1 to 32"), std::string::npos);
  const InputField wide[] = {{"a", InputFieldType::kU8, 0, 0, 256}};
  EXPECT_EQ(message({"x", 8, wide, nullptr}),
            "input field 0 ('a'): range [0, 256] is empty or does not fit the field's type");
  const InputField empty[] = {{"a", InputFieldType::kI8, 0, 5, 4}};
  EXPECT_NE(message({"x", 8, empty, nullptr}).find("is empty"), std::string::npos);
}

TEST(InputSpec, DescribeRandomAndPredict) {
  const PlayerInput input = PlayerInput::of(CarInput{-7, 30, 1, 9});
  EXPECT_EQ(describe_input(kCarSpec, input), "steer=-7 throttle=30 brake=1 horn=9");
  EXPECT_EQ(describe_input(stick_input_spec(), stick_input(12, -40, 3)),
            "axis_x=12 axis_y=-40 buttons=3");
  EXPECT_EQ(find_input_field(kCarSpec, "brake"), &kCarFields[2]);
  EXPECT_EQ(find_input_field(kCarSpec, "horns"), nullptr);
  const InputSpec opaque{"blob", 3, {}, nullptr};
  PlayerInput blob;
  blob.bytes = {0x0A, 0xFF, 0x00};
  EXPECT_EQ(describe_input(opaque, blob), "0aff00");

  // Random inputs always pass the spec, differ with the bits and repeat with them.
  bool varied = false;
  for (uint64_t bits = 0; bits < 200; ++bits) {
    const PlayerInput r = random_input(kCarSpec, bits);
    ASSERT_TRUE(check_input(kCarSpec, r).ok()) << describe_input(kCarSpec, r);
    EXPECT_EQ(r, random_input(kCarSpec, bits));
    varied = varied || !(r == random_input(kCarSpec, 0));
  }
  EXPECT_TRUE(varied);
  EXPECT_TRUE(check_input(opaque, random_input(opaque, 5)).ok());

  // The spec's predictor, or the newest input itself without one.
  const PlayerInput braking = PlayerInput::of(CarInput{100, 50, 1, 0});
  EXPECT_EQ(predict_input(kCarSpec, braking), PlayerInput::of(CarInput{100, 50, 0, 0}));
  EXPECT_EQ(predict_input(stick_input_spec(), stick_input(1, 2, 3)), stick_input(1, 2, 3));
}

}  // namespace
}  // namespace rwd
