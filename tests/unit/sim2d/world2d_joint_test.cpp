// SPDX-License-Identifier: MIT
// Joints of the 2D lane against what each one promises, and through
// save/restore and the snapshot bytes.
#include <vector>

#include "rewind/fixed/fx_math.h"
#include "rewind/sim2d/world2d.h"
#include "world2d_test_scenes.h"

namespace rwd::sim2d {
namespace {

using testing::add_body;

double to_double(Fx f) {
  return f.raw() / 65536.0;
}

JointDef2D joint_at(JointType2D type, BodyId2D a, BodyId2D b, Vec2 anchor) {
  JointDef2D def;
  def.type = type;
  def.body_a = a;
  def.body_b = b;
  def.anchor_a = anchor;
  def.anchor_b = anchor;
  return def;
}

TEST(World2DJoints, PendulumPeriodMatchesSmallAngleTheory) {
  // A 1 m pendulum (a small heavy disc) swinging 0.1 rad: T = 2 pi sqrt(L / g)
  // = 1.98692 s at g = 10. Counted from the zero crossings of x over three
  // periods; within 1%.
  World2D world;
  const BodyId2D pivot = add_body(world, BodyKind2D::kStatic, make_circle(0.05_fx), {Fx(), 2_fx});
  // sin(0.1) = 0.0998, cos(0.1) = 0.995: the bob starts 0.1 rad out.
  const BodyId2D bob =
      add_body(world, BodyKind2D::kDynamic, make_circle(0.05_fx), {0.0998_fx, 2_fx - 0.995_fx});
  JointDef2D rod = joint_at(JointType2D::kDistance, pivot, bob, {Fx(), 2_fx});
  rod.anchor_b = world.position(bob);
  rod.length = 1_fx;
  ASSERT_TRUE(world.create_joint(rod).ok());
  int crossings = 0;
  int first = -1;
  int last = -1;
  Fx previous = world.position(bob).x;
  for (int t = 1; t <= 60 * 8 && crossings < 7; ++t) {
    world.step();
    const Fx x = world.position(bob).x;
    if ((previous > Fx()) != (x > Fx())) {
      ++crossings;
      if (first < 0) first = t;
      last = t;
    }
    previous = x;
  }
  ASSERT_EQ(crossings, 7);
  const double period = (last - first) / 60.0 / 3.0;
  EXPECT_NEAR(period, 1.98692, 0.0199);
}

TEST(World2DJoints, RevolutePendulumKeepsItsPivotAndPeriod) {
  // A uniform rod of length 1 m hinged at one end: T = 2 pi sqrt(2 L / (3 g))
  // = 1.62231 s for small swings.
  World2D world;
  const BodyId2D ground = add_body(world, BodyKind2D::kStatic, make_circle(0.05_fx), {Fx(), 3_fx});
  // The rod hangs from (0, 3), turned 0.1 rad: its centre 0.5 m along it.
  BodyDef2D def;
  def.shape = *make_box(0.5_fx, 0.02_fx);
  def.angle = -Fx::half_pi() + 0.1_fx;
  def.position = {0.0499_fx, 3_fx - 0.4975_fx};
  const BodyId2D rod = *world.create_body(def);
  const JointId2D hinge =
      *world.create_joint(joint_at(JointType2D::kRevolute, ground, rod, {Fx(), 3_fx}));
  EXPECT_TRUE(world.is_valid(hinge));
  int crossings = 0;
  int first = -1;
  int last = -1;
  Fx previous = world.center_of_mass(rod).x;
  for (int t = 1; t <= 60 * 8 && crossings < 7; ++t) {
    world.step();
    const Fx x = world.center_of_mass(rod).x;
    if ((previous > Fx()) != (x > Fx())) {
      ++crossings;
      if (first < 0) first = t;
      last = t;
    }
    previous = x;
    // The hinge holds: the rod's end stays at the pivot within 1 mm.
    const fixed::Rot2 q = world.rotation(rod);
    const Vec2 end = world.position(rod) + fixed::rotate(q, Vec2{-0.5_fx, Fx()});
    EXPECT_LT(fixed::length(end - Vec2{Fx(), 3_fx}), 0.001_fx) << "tick " << t;
  }
  ASSERT_EQ(crossings, 7);
  EXPECT_NEAR((last - first) / 60.0 / 3.0, 1.62231, 0.0162);
}

TEST(World2DJoints, RevoluteLimitAndMotor) {
  World2DConfig config;
  config.gravity = {};
  World2D world(config);
  const BodyId2D ground = add_body(world, BodyKind2D::kStatic, make_circle(0.1_fx), {});
  const BodyId2D arm = add_body(world, BodyKind2D::kDynamic, make_box(1_fx, 0.1_fx), {1_fx, Fx()});
  JointDef2D def = joint_at(JointType2D::kRevolute, ground, arm, {});
  def.enable_motor = true;
  def.motor_speed = 2_fx;
  def.max_motor = 100_fx;
  def.enable_limit = true;
  def.lower = -0.5_fx;
  def.upper = 0.75_fx;
  const JointId2D hinge = *world.create_joint(def);
  for (int t = 0; t < 15; ++t) world.step();
  // Driven at 2 rad/s for 0.25 s: 0.5 rad, below the limit.
  EXPECT_NEAR(to_double(world.angle(arm)), 0.5, 0.02);
  for (int t = 0; t < 60; ++t) world.step();
  // Held at the upper limit.
  EXPECT_NEAR(to_double(world.angle(arm)), 0.75, 0.01);
  ASSERT_TRUE(world.set_motor_speed(hinge, -3_fx).ok());
  for (int t = 0; t < 90; ++t) world.step();
  EXPECT_NEAR(to_double(world.angle(arm)), -0.5, 0.01);
}

TEST(World2DJoints, ReferenceAngleMovesTheSpringsRestAndTheLimits) {
  // A hinged arm without gravity, its spring's rest 0.6 rad from the pose at
  // creation: the spring turns it there. A second arm whose limits [-0.2,
  // 0.3] are counted from a reference of 0.5 starts at -0.5 on the joint's
  // scale; a motor turns it down against the lower limit, which holds it
  // 0.3 rad from where it started.
  World2DConfig config;
  config.gravity = {};
  World2D world(config);
  const BodyId2D ground = add_body(world, BodyKind2D::kStatic, make_circle(0.1_fx), {});
  const BodyId2D sprung =
      add_body(world, BodyKind2D::kDynamic, make_box(1_fx, 0.1_fx), {1_fx, Fx()});
  JointDef2D spring = joint_at(JointType2D::kRevolute, ground, sprung, {});
  spring.enable_spring = true;
  spring.hertz = 2_fx;
  spring.damping_ratio = 1_fx;
  spring.reference_angle = 0.6_fx;
  ASSERT_TRUE(world.create_joint(spring).ok());
  const BodyId2D limited =
      add_body(world, BodyKind2D::kDynamic, make_box(1_fx, 0.1_fx), {1_fx, 5_fx});
  const BodyId2D pin = add_body(world, BodyKind2D::kStatic, make_circle(0.1_fx), {Fx(), 5_fx});
  JointDef2D limit = joint_at(JointType2D::kRevolute, pin, limited, {Fx(), 5_fx});
  limit.enable_limit = true;
  limit.lower = -0.2_fx;
  limit.upper = 0.3_fx;
  limit.reference_angle = 0.5_fx;
  limit.enable_motor = true;
  limit.motor_speed = -1_fx;
  limit.max_motor = 5_fx;
  ASSERT_TRUE(world.create_joint(limit).ok());
  for (int t = 0; t < 180; ++t) world.step();
  EXPECT_NEAR(to_double(world.angle(sprung)), 0.6, 0.01);
  EXPECT_NEAR(to_double(world.angle(limited)), 0.3, 0.01);

  // Outside [-pi, pi] it is refused and nothing changes.
  const uint32_t joints = world.joint_count();
  JointDef2D bad = spring;
  bad.reference_angle = Fx::pi() + Fx::epsilon();
  EXPECT_FALSE(world.create_joint(bad).ok());
  EXPECT_EQ(world.joint_count(), joints);
}

TEST(World2DJoints, PrismaticSlidesOnlyAlongItsAxisWithinLimits) {
  World2D world;  // gravity pulls down; the axis is diagonal
  const BodyId2D ground = add_body(world, BodyKind2D::kStatic, make_circle(0.1_fx), {});
  const BodyId2D slider = add_body(world, BodyKind2D::kDynamic, make_box(0.2_fx, 0.2_fx), {});
  JointDef2D def = joint_at(JointType2D::kPrismatic, ground, slider, {});
  def.axis = {1_fx, 1_fx};
  def.enable_limit = true;
  def.lower = -1_fx;
  def.upper = 1_fx;
  ASSERT_TRUE(world.create_joint(def).ok());
  for (int t = 0; t < 120; ++t) {
    world.step();
    const Vec2 p = world.position(slider);
    EXPECT_LT(fixed::abs(p.x - p.y), 0.002_fx) << "off the axis at tick " << t;
    EXPECT_LT(fixed::abs(world.angle(slider)), 0.002_fx) << "turned at tick " << t;
  }
  // It slid down to the lower limit: 1 m along (1, 1) / sqrt(2).
  EXPECT_NEAR(to_double(world.position(slider).x), -0.70711, 0.005);
}

TEST(World2DJoints, WheelSuspensionSettlesAtTheStaticSag) {
  // A 1 kg wheel hung on a vertical 4 Hz suspension sags m g / k, with
  // k = m (2 pi f)^2: 10 / 631.65 = 15.8 mm.
  World2D world;
  const BodyId2D chassis =
      add_body(world, BodyKind2D::kStatic, make_box(1_fx, 0.1_fx), {Fx(), 2_fx});
  BodyDef2D wheel_def;
  wheel_def.shape = *make_circle(0.3_fx);
  wheel_def.position = {Fx(), 1_fx};
  wheel_def.density = Fx::ratio(1, 1) / (Fx::pi() * 0.09_fx);  // 1 kg
  const BodyId2D wheel = *world.create_body(wheel_def);
  JointDef2D def = joint_at(JointType2D::kWheel, chassis, wheel, {Fx(), 1_fx});
  def.axis = {Fx(), 1_fx};
  def.hertz = 4_fx;
  def.damping_ratio = 0.7_fx;
  ASSERT_TRUE(world.create_joint(def).ok());
  for (int t = 0; t < 240; ++t) world.step();
  EXPECT_NEAR(to_double(world.position(wheel).y), 1.0 - 0.0158, 0.0015);
  EXPECT_NEAR(to_double(world.position(wheel).x), 0.0, 0.001);
}

TEST(World2DJoints, WeldHoldsACantileverAndGrabPullsToTheTarget) {
  World2D world;
  const BodyId2D wall = add_body(world, BodyKind2D::kStatic, make_box(0.1_fx, 1_fx), {});
  const BodyId2D beam =
      add_body(world, BodyKind2D::kDynamic, make_box(1_fx, 0.1_fx), {1.1_fx, Fx()});
  ASSERT_TRUE(world.create_joint(joint_at(JointType2D::kWeld, wall, beam, {0.1_fx, Fx()})).ok());
  const BodyId2D ball = add_body(world, BodyKind2D::kDynamic, make_circle(0.2_fx), {-3_fx, Fx()});
  JointDef2D grab = joint_at(JointType2D::kGrab, wall, ball, {-3_fx, Fx()});
  grab.target = {-3_fx, 2_fx};
  grab.hertz = 5_fx;
  grab.damping_ratio = 1_fx;
  grab.max_force = 100_fx;
  ASSERT_TRUE(world.create_joint(grab).ok());
  for (int t = 0; t < 180; ++t) world.step();
  // The beam droops by less than 2 cm at its tip and barely turns.
  EXPECT_GT(world.position(beam).y, -0.02_fx);
  EXPECT_LT(fixed::abs(world.angle(beam)), 0.02_fx);
  // The ball hangs just under the target: the spring's sag is g / (2 pi 5)^2.
  EXPECT_NEAR(to_double(world.position(ball).y), 2.0 - 0.0101, 0.003);
}

TEST(World2DJoints, BreakImpulseBreaksAndConnectedBodiesDoNotCollide) {
  World2D world;
  const BodyId2D ceiling =
      add_body(world, BodyKind2D::kStatic, make_box(1_fx, 0.1_fx), {Fx(), 2_fx});
  // A heavy box overlapping its ceiling: joined without collide_connected,
  // so they do not push apart.
  BodyDef2D heavy;
  heavy.shape = *make_box(0.5_fx, 0.5_fx);
  heavy.position = {Fx(), 1.8_fx};
  heavy.density = 10_fx;  // 10 kg: 100 N / 60 Hz = 1.67 N s a tick
  const BodyId2D box = *world.create_body(heavy);
  JointDef2D def = joint_at(JointType2D::kRevolute, ceiling, box, {Fx(), 1.8_fx});
  def.break_impulse = 2_fx;
  const JointId2D hinge = *world.create_joint(def);
  for (int t = 0; t < 15; ++t) world.step();
  EXPECT_FALSE(world.is_joint_broken(hinge));
  EXPECT_NEAR(to_double(world.position(box).y), 1.8, 0.002);
  // Pulled down with 200 N more for one tick: 5 N s, the hinge breaks and
  // the box falls.
  ASSERT_TRUE(world.apply_force(box, {Fx(), -200_fx}).ok());
  world.step();
  EXPECT_TRUE(world.is_joint_broken(hinge));
  for (int t = 0; t < 30; ++t) world.step();
  EXPECT_LT(world.position(box).y, 1.5_fx);
}

TEST(World2DJoints, JointsSurviveRestoreAndSnapshotBytes) {
  World2D world;
  const BodyId2D ground =
      add_body(world, BodyKind2D::kStatic, make_box(5_fx, 0.5_fx), {Fx(), -0.5_fx});
  // A chain of 8 links hanging from a pivot, swinging into the ground.
  BodyId2D previous = ground;
  Vec2 anchor{-2_fx, 3_fx};
  for (int i = 0; i < 8; ++i) {
    const BodyId2D link = add_body(world, BodyKind2D::kDynamic,
                                   make_capsule({-0.2_fx, Fx()}, {0.2_fx, Fx()}, 0.05_fx),
                                   anchor + Vec2{0.2_fx, Fx()});
    JointDef2D def = joint_at(JointType2D::kRevolute, previous, link, anchor);
    ASSERT_TRUE(world.create_joint(def).ok());
    previous = link;
    anchor = anchor + Vec2{0.4_fx, Fx()};
  }
  EXPECT_EQ(world.joint_count(), 8u);
  for (int t = 0; t < 40; ++t) world.step();
  World2DState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> expected;
  for (int t = 0; t < 80; ++t) {
    world.step();
    expected.push_back(world.checksum());
  }
  world.restore(saved);
  World2D copy;
  ASSERT_TRUE(copy.deserialize(bytes).ok());
  for (size_t t = 0; t < expected.size(); ++t) {
    world.step();
    copy.step();
    ASSERT_EQ(world.checksum(), expected[t]) << t;
    ASSERT_EQ(copy.checksum(), expected[t]) << t;
  }
  // Destroying a body destroys its joints.
  ASSERT_TRUE(world.destroy_body(previous).ok());
  EXPECT_EQ(world.joint_count(), 7u);
}

// Static and kinematic bodies on both sides (Box2D's joint grid has six
// such joints): every type is accepted and kept, moves nothing, takes no
// impulse, saves and reloads, and can be destroyed.
struct NonDynamicScene {
  BodyId2D ground;
  BodyId2D post;
  BodyId2D spinner;  ///< kinematic, moving and turning
  BodyId2D lift;     ///< kinematic, moving
  BodyId2D parked;   ///< kinematic, still
};

NonDynamicScene build_non_dynamic(World2D& world) {
  NonDynamicScene s;
  s.ground = add_body(world, BodyKind2D::kStatic, make_box(5_fx, 0.5_fx), {Fx(), -0.5_fx});
  s.post = add_body(world, BodyKind2D::kStatic, make_box(0.1_fx, 1_fx), {6_fx, 1_fx});
  s.spinner = add_body(world, BodyKind2D::kKinematic, make_box(1_fx, 0.1_fx), {Fx(), 3_fx});
  s.lift = add_body(world, BodyKind2D::kKinematic, make_circle(0.5_fx), {3_fx, 6_fx});
  s.parked = add_body(world, BodyKind2D::kKinematic, make_capsule({}, {1_fx, Fx()}, 0.2_fx),
                      {-3_fx, 4_fx});
  EXPECT_TRUE(world.set_linear_velocity(s.spinner, {1_fx, 0.25_fx}).ok());
  EXPECT_TRUE(world.set_angular_velocity(s.spinner, 0.5_fx).ok());
  EXPECT_TRUE(world.set_linear_velocity(s.lift, {Fx(), -0.5_fx}).ok());
  // A ball falling beside them keeps the step's other stages busy.
  add_body(world, BodyKind2D::kDynamic, make_circle(0.25_fx), {-6_fx, 2_fx});
  return s;
}

std::vector<JointId2D> join_non_dynamic(World2D& world, const NonDynamicScene& s) {
  const BodyId2D pairs[4][2] = {
      {s.ground, s.spinner}, {s.spinner, s.lift}, {s.ground, s.post}, {s.lift, s.parked}};
  const JointType2D types[6] = {JointType2D::kDistance,  JointType2D::kRevolute,
                                JointType2D::kPrismatic, JointType2D::kWheel,
                                JointType2D::kWeld,      JointType2D::kGrab};
  std::vector<JointId2D> joints;
  for (const auto& pair : pairs) {
    for (const JointType2D type : types) {
      JointDef2D def = joint_at(type, pair[0], pair[1], {1_fx, 2_fx});
      def.anchor_b = {2_fx, 3_fx};
      def.length = 0.5_fx;  // far from the anchors' distance: a large error
      def.enable_limit = true;
      def.lower = -0.1_fx;
      def.upper = 0.1_fx;
      def.enable_motor = true;
      def.motor_speed = 5_fx;
      def.max_motor = 1000_fx;
      def.enable_spring = type != JointType2D::kRevolute;
      def.linear_hertz = 2_fx;
      def.target = {-20_fx, 20_fx};
      def.break_impulse = Fx::epsilon();  // any impulse at all would break it
      const Result<JointId2D> id = world.create_joint(def);
      EXPECT_TRUE(id.ok()) << static_cast<int>(type) << ": " << id.status().message();
      if (id.ok()) joints.push_back(*id);
    }
  }
  return joints;
}

TEST(World2DJoints, JointsBetweenStaticAndKinematicBodiesMoveNothing) {
  World2D world;
  World2D plain;  // the same bodies without the joints
  const NonDynamicScene s = build_non_dynamic(world);
  build_non_dynamic(plain);
  const std::vector<JointId2D> joints = join_non_dynamic(world, s);
  ASSERT_EQ(joints.size(), 24u);
  EXPECT_EQ(world.joint_count(), 24u);
  std::vector<BodyId2D> ids;
  world.body_ids(ids);
  for (int t = 0; t < 120; ++t) {
    world.step();
    plain.step();
  }
  // Kinematic bodies kept the velocities they were given, exactly.
  for (const BodyId2D id : ids) {
    EXPECT_EQ(world.position(id), plain.position(id)) << id.index;
    EXPECT_EQ(world.rotation(id).c, plain.rotation(id).c) << id.index;
    EXPECT_EQ(world.rotation(id).s, plain.rotation(id).s) << id.index;
    EXPECT_EQ(world.linear_velocity(id), plain.linear_velocity(id)) << id.index;
    EXPECT_EQ(world.angular_velocity(id), plain.angular_velocity(id)) << id.index;
  }
  EXPECT_NEAR(to_double(world.position(s.spinner).x), 2.0, 0.001);
  EXPECT_NEAR(to_double(world.position(s.lift).y), 5.0, 0.001);
  // No impulse at all: nothing broke, no force is reported.
  for (const JointId2D j : joints) {
    EXPECT_TRUE(world.is_valid(j));
    EXPECT_FALSE(world.is_joint_broken(j)) << j.index;
    EXPECT_EQ(world.joint_force(j), Vec2{}) << j.index;
    const JointRecord2D& record = world.state().joints[j.index];
    EXPECT_EQ(record.linear_impulse, detail::V2{});
    EXPECT_EQ(record.angular_impulse | record.axial_impulse | record.spring_impulse |
                  record.motor_impulse | record.lower_impulse | record.upper_impulse,
              0);
  }
  // Steering them is accepted too.
  EXPECT_TRUE(world.set_motor_speed(joints[1], -2_fx).ok());
  EXPECT_TRUE(world.set_grab_target(joints[5], {1_fx, 1_fx}).ok());
  for (size_t k = 0; k < joints.size(); k += 2) {
    ASSERT_TRUE(world.destroy_joint(joints[k]).ok());
    EXPECT_FALSE(world.is_valid(joints[k]));
  }
  EXPECT_EQ(world.joint_count(), 12u);
  // Destroying a body takes its joints: the spinner is in 12 of the 24,
  // 6 of them left.
  ASSERT_TRUE(world.destroy_body(s.spinner).ok());
  EXPECT_EQ(world.joint_count(), 6u);
}

TEST(World2DJoints, JointsBetweenStaticAndKinematicBodiesRestoreAndReload) {
  World2D world;
  const NonDynamicScene s = build_non_dynamic(world);
  join_non_dynamic(world, s);
  for (int t = 0; t < 20; ++t) world.step();
  World2DState saved;
  world.save(saved);
  std::vector<uint8_t> bytes;
  world.serialize(bytes);
  std::vector<uint64_t> expected;
  for (int t = 0; t < 60; ++t) {
    world.step();
    expected.push_back(world.checksum());
  }
  world.restore(saved);
  World2D copy;
  ASSERT_TRUE(copy.deserialize(bytes).ok());
  EXPECT_EQ(copy.joint_count(), 24u);
  for (size_t t = 0; t < expected.size(); ++t) {
    world.step();
    copy.step();
    ASSERT_EQ(world.checksum(), expected[t]) << t;
    ASSERT_EQ(copy.checksum(), expected[t]) << t;
  }
  std::vector<uint8_t> again;
  copy.serialize(again);
  world.serialize(bytes);
  EXPECT_EQ(again, bytes);
}

}  // namespace
}  // namespace rwd::sim2d
