// SPDX-License-Identifier: MIT
// Per-body event masks: each bit lets one event type through (enter, stay,
// exit; solid contacts and sensor overlaps apart), either body's mask
// reports a pair, the boolean contact_events maps onto the mask, and the
// mask is state (restore, snapshots, checksum, dump) that keeps default
// worlds' bytes and checksums as they were.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "rewind/sim/world3d.h"
#include "sim_test_scenes.h"

namespace rwd::sim {
namespace {

using test::add_box;
using test::add_ground;

struct Counts {
  int enter = 0;
  int stay = 0;
  int exit = 0;
  int sensor = 0;  ///< of all types
  int solid = 0;
};

void add_events(const World3D& world, Counts& c) {
  for (const ContactEvent& e : world.events()) {
    c.enter += e.type == ContactEventType::kEnter ? 1 : 0;
    c.stay += e.type == ContactEventType::kStay ? 1 : 0;
    c.exit += e.type == ContactEventType::kExit ? 1 : 0;
    (e.sensor ? c.sensor : c.solid) += 1;
  }
}

// A box set on the ground (enter, then stays) and lifted off (exit), with
// the ground asking for nothing and the box for `mask`.
Counts solid_sequence(EventMask mask) {
  World3D world;
  const BodyId ground = add_ground(world);
  EXPECT_TRUE(world.set_event_mask(ground, kEventNone).ok());
  BodyDef def;
  def.position = {0.0f, 0.5f, 0.0f};
  def.event_mask = mask;
  const BodyId box = *world.create_body(def);
  Counts c;
  for (int i = 0; i < 5; ++i) {
    world.step();
    add_events(world, c);
  }
  EXPECT_TRUE(world.set_transform(box, {0.0f, 5.0f, 0.0f}, Quat{}).ok());
  world.step();
  add_events(world, c);
  return c;
}

TEST(EventMasks, EachSolidBitLetsItsTypeThrough) {
  const Counts all = solid_sequence(kEventAll);
  EXPECT_EQ(all.enter, 1);
  EXPECT_EQ(all.stay, 4);
  EXPECT_EQ(all.exit, 1);
  const Counts enter = solid_sequence(kEventContactEnter);
  EXPECT_EQ(enter.enter, 1);
  EXPECT_EQ(enter.stay + enter.exit, 0);
  const Counts stay = solid_sequence(kEventContactStay);
  EXPECT_EQ(stay.stay, 4);
  EXPECT_EQ(stay.enter + stay.exit, 0);
  const Counts exit = solid_sequence(kEventContactExit);
  EXPECT_EQ(exit.exit, 1);
  EXPECT_EQ(exit.enter + exit.stay, 0);
  // Sensor bits say nothing about solid contacts.
  const Counts sensor = solid_sequence(kEventSensorAll);
  EXPECT_EQ(sensor.enter + sensor.stay + sensor.exit, 0);
  const Counts none = solid_sequence(kEventNone);
  EXPECT_EQ(none.enter + none.stay + none.exit, 0);
}

// A ball that rests on the ground inside a sensor zone, then is lifted
// out of both: one solid and one sensor pair. The ground and the zone ask
// for nothing; the ball for `mask`.
Counts sensor_sequence(EventMask mask) {
  World3D world;
  const BodyId ground = add_ground(world);
  EXPECT_TRUE(world.set_contact_events(ground, false).ok());
  BodyDef zone;
  zone.kind = BodyKind::kStatic;
  zone.sensor = true;
  zone.shape = Shape::make_box({1.0f, 1.0f, 1.0f});
  zone.position = {0.0f, 1.0f, 0.0f};
  zone.contact_events = false;
  (void)*world.create_body(zone);
  BodyDef ball;
  ball.shape = Shape::make_sphere(0.5f);
  ball.position = {0.0f, 0.5f, 0.0f};
  ball.event_mask = mask;
  const BodyId b = *world.create_body(ball);
  Counts c;
  for (int i = 0; i < 5; ++i) {
    world.step();
    add_events(world, c);
  }
  EXPECT_TRUE(world.set_transform(b, {0.0f, 8.0f, 0.0f}, Quat{}).ok());
  world.step();
  add_events(world, c);
  return c;
}

TEST(EventMasks, SensorBitsAndSolidBitsAreApart) {
  const Counts all = sensor_sequence(kEventAll);
  EXPECT_EQ(all.sensor, 6);  // enter, 4 stays, exit
  EXPECT_EQ(all.solid, 6);
  const Counts sensors = sensor_sequence(kEventSensorAll);
  EXPECT_EQ(sensors.sensor, 6);
  EXPECT_EQ(sensors.solid, 0);
  const Counts solids = sensor_sequence(kEventContactAll);
  EXPECT_EQ(solids.sensor, 0);
  EXPECT_EQ(solids.solid, 6);
  const Counts sensor_enter = sensor_sequence(kEventSensorEnter);
  EXPECT_EQ(sensor_enter.sensor, 1);
  EXPECT_EQ(sensor_enter.enter, 1);
  EXPECT_EQ(sensor_enter.solid, 0);
  const Counts sensor_stay = sensor_sequence(kEventSensorStay);
  EXPECT_EQ(sensor_stay.sensor, 4);
  EXPECT_EQ(sensor_stay.stay, 4);
  const Counts sensor_exit = sensor_sequence(kEventSensorExit | kEventContactEnter);
  EXPECT_EQ(sensor_exit.sensor, 1);
  EXPECT_EQ(sensor_exit.solid, 1);
  EXPECT_EQ(sensor_exit.enter, 1);  // the ground's
  EXPECT_EQ(sensor_exit.exit, 1);   // the zone's
}

TEST(EventMasks, EitherBodysMaskReportsThePair) {
  World3D world;
  const BodyId ground = add_ground(world);
  ASSERT_TRUE(world.set_event_mask(ground, kEventContactEnter).ok());
  BodyDef def;
  def.position = {0.0f, 0.5f, 0.0f};
  def.event_mask = kEventContactExit;
  const BodyId box = *world.create_body(def);
  Counts c;
  for (int i = 0; i < 3; ++i) {
    world.step();
    add_events(world, c);
  }
  ASSERT_TRUE(world.set_transform(box, {0.0f, 5.0f, 0.0f}, Quat{}).ok());
  world.step();
  add_events(world, c);
  EXPECT_EQ(c.enter, 1);
  EXPECT_EQ(c.stay, 0);
  EXPECT_EQ(c.exit, 1);
}

TEST(EventMasks, ADestroyedBodysExitIsNotLost) {
  World3D world;
  const BodyId ground = add_ground(world);
  ASSERT_TRUE(world.set_event_mask(ground, kEventNone).ok());
  BodyDef def;
  def.position = {0.0f, 0.5f, 0.0f};
  def.event_mask = kEventContactEnter;
  const BodyId box = *world.create_body(def);
  world.step();
  ASSERT_EQ(world.events().size(), 1u);
  ASSERT_TRUE(world.destroy_body(box).ok());
  world.step();
  ASSERT_EQ(world.events().size(), 1u);
  EXPECT_EQ(world.events()[0].type, ContactEventType::kExit);
}

TEST(EventMasks, TheBooleanMapsOntoTheMask) {
  World3D world;
  BodyDef def;
  EXPECT_EQ(def.event_mask, kEventAll);
  const BodyId loud = *world.create_body(def);
  EXPECT_EQ(world.event_mask(loud), kEventAll);
  def.position = {3.0f, 0.0f, 0.0f};
  def.contact_events = false;
  def.event_mask = kEventContactEnter;  // contact_events = false wins
  const BodyId quiet = *world.create_body(def);
  EXPECT_EQ(world.event_mask(quiet), kEventNone);
  ASSERT_TRUE(world.set_contact_events(quiet, true).ok());
  EXPECT_EQ(world.event_mask(quiet), kEventAll);
  ASSERT_TRUE(world.set_contact_events(loud, false).ok());
  EXPECT_EQ(world.event_mask(loud), kEventNone);
  ASSERT_TRUE(world.set_event_mask(loud, kEventSensorEnter | kEventContactExit).ok());
  EXPECT_EQ(world.event_mask(loud), kEventSensorEnter | kEventContactExit);
  EXPECT_EQ(world.event_mask(BodyId{77, 1}), kEventNone);
}

TEST(EventMasks, BadMasksAndIdsAreRefusedAndChangeNothing) {
  World3D world;
  const BodyId box = add_box(world, {0.0f, 1.0f, 0.0f});
  ASSERT_TRUE(world.set_event_mask(box, kEventContactStay).ok());
  const uint64_t before = world.checksum();
  EXPECT_EQ(world.set_event_mask(box, 0x40).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.set_event_mask(box, 0xFF).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.set_event_mask(BodyId{9, 1}, kEventAll).code(), ErrorCode::kNotFound);
  EXPECT_EQ(world.checksum(), before);
  EXPECT_EQ(world.event_mask(box), kEventContactStay);
  BodyDef def;
  def.event_mask = 0x80;
  const auto refused = world.create_body(def);
  EXPECT_EQ(refused.status().code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(world.body_count(), 1u);
  EXPECT_EQ(world.checksum(), before);
}

TEST(EventMasks, AllOrNothingMasksHashAsTheBooleanDid) {
  // Every mask the boolean can make keeps the checksum a world of
  // booleans had; only a selection changes it, and each selection apart.
  World3D a;
  World3D b;
  const BodyId in_a = add_box(a, {0.0f, 1.0f, 0.0f});
  const BodyId in_b = add_box(b, {0.0f, 1.0f, 0.0f});
  ASSERT_TRUE(a.set_contact_events(in_a, false).ok());
  ASSERT_TRUE(b.set_event_mask(in_b, kEventNone).ok());
  EXPECT_EQ(a.checksum(), b.checksum());
  ASSERT_TRUE(a.set_event_mask(in_a, kEventAll).ok());
  ASSERT_TRUE(b.set_contact_events(in_b, true).ok());
  EXPECT_EQ(a.checksum(), b.checksum());
  const uint64_t all = a.checksum();
  ASSERT_TRUE(a.set_event_mask(in_a, kEventContactEnter).ok());
  const uint64_t enter = a.checksum();
  ASSERT_TRUE(a.set_event_mask(in_a, kEventContactStay).ok());
  const uint64_t stay = a.checksum();
  EXPECT_NE(enter, all);
  EXPECT_NE(stay, all);
  EXPECT_NE(enter, stay);
}

TEST(EventMasks, MasksSurviveRestoreSnapshotsAndTheDump) {
  World3D world;
  add_ground(world);
  const BodyId box = add_box(world, {0.0f, 0.5f, 0.0f});
  const EventMask mask = kEventContactEnter | kEventSensorExit;
  ASSERT_TRUE(world.set_event_mask(box, mask).ok());
  WorldState saved;
  world.save(saved);
  const uint64_t sum = world.checksum();
  ASSERT_TRUE(world.set_event_mask(box, kEventAll).ok());
  EXPECT_NE(world.checksum(), sum);
  world.restore(saved);
  EXPECT_EQ(world.event_mask(box), mask);
  EXPECT_EQ(world.checksum(), sum);

  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  World3D loaded;
  ASSERT_TRUE(loaded.deserialize(bytes).ok());
  EXPECT_EQ(loaded.event_mask(box), mask);
  EXPECT_EQ(loaded.checksum(), sum);
  std::string text;
  loaded.dump_state(text);
  EXPECT_NE(text.find("body[1].event_mask = " + std::to_string(mask) + "\n"), std::string::npos)
      << text;

  // The loaded world reports as the saved one does.
  world.step();
  loaded.step();
  ASSERT_EQ(world.events().size(), 1u);
  ASSERT_EQ(loaded.events().size(), 1u);
  EXPECT_EQ(loaded.events()[0].type, ContactEventType::kEnter);
  EXPECT_EQ(world.checksum(), loaded.checksum());
}

TEST(EventMasks, SnapshotRefusesAMaskByteNoWorldWrites) {
  // Find the mask's byte: the only one that differs between a body that
  // reports everything (1) and one that reports a selection (0x80 | bits).
  World3D world;
  const BodyId box = add_box(world, {0.0f, 1.0f, 0.0f});
  std::vector<uint8_t> all;
  world.serialize(all);
  ASSERT_TRUE(world.set_event_mask(box, kEventContactEnter).ok());
  std::vector<uint8_t> selection;
  world.serialize(selection);
  ASSERT_EQ(all.size(), selection.size());
  size_t at = all.size();
  for (size_t i = 0; i < all.size(); ++i) {
    if (all[i] != selection[i]) {
      ASSERT_EQ(at, all.size()) << "more than one byte differs";
      at = i;
    }
  }
  ASSERT_LT(at, all.size());
  EXPECT_EQ(all[at], 1);
  EXPECT_EQ(selection[at], 0x81);
  for (const uint8_t bad :
       {uint8_t{2}, uint8_t{0x40}, uint8_t{0x80}, uint8_t{0xBF}, uint8_t{0xC1}}) {
    std::vector<uint8_t> bytes = selection;
    bytes[at] = bad;
    World3D target;
    const uint64_t before = target.checksum();
    const Status s = target.deserialize(bytes);
    EXPECT_EQ(s.code(), ErrorCode::kCorrupt) << int{bad};
    EXPECT_EQ(target.checksum(), before);
  }
}

}  // namespace
}  // namespace rwd::sim
