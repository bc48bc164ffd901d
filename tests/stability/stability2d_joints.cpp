// SPDX-License-Identifier: MIT
// 2D scenes where jointed solvers fail: a chain holding a ball a hundred
// times heavier than a link, a plank bridge under load, and a pile of
// ragdolls. Each states its criterion; each replays bit for bit.
#include "rewind/fixed/trig.h"
#include "scene2d.h"

namespace rwd::sim2d {
namespace {

using namespace scene;  // NOLINT: test brevity

JointDef2D revolute(BodyId2D a, BodyId2D b, Vec2 at) {
  JointDef2D j;
  j.type = JointType2D::kRevolute;
  j.body_a = a;
  j.body_b = b;
  j.anchor_a = at;
  j.anchor_b = at;
  return j;
}

// A chain of 10 capsule links (0.5 m each) hanging from a pin, with a ball
// of 100 times a link's mass on its end. The joints are soft (a spring of
// twice the contact hertz sized to the light links' mass), so the chain
// stretches under the heavy ball; criterion: after 8 s the stretch is under
// 5% of the chain's 5.5 m (0.275 m; measured about 3%), the ball hangs
// still (slower than 0.1 m/s) and the chain never came apart (never more
// than 10% of its length longer).
TEST(Stability2D, ChainHoldsABallAHundredTimesHeavierThanALink) {
  World2D world;
  const BodyId2D pin =
      add(world, def(make_circle(0.1_fx), {Fx(), 20_fx}, Fx(), BodyKind2D::kStatic));
  BodyId2D previous = pin;
  Vec2 anchor{Fx(), 20_fx};
  for (int i = 0; i < 10; ++i) {
    const BodyId2D link = add(world, def(make_capsule({Fx(), -0.25_fx}, {Fx(), 0.25_fx}, 0.1_fx),
                                         {Fx(), anchor.y - 0.25_fx}));
    ASSERT_TRUE(world.create_joint(revolute(previous, link, anchor)).ok());
    previous = link;
    anchor.y -= 0.5_fx;
  }
  const Fx link_mass = world.mass(previous).to_fx();
  BodyDef2D ball = def(make_circle(0.5_fx), {Fx(), anchor.y - 0.5_fx});
  ball.density = link_mass * 100 / (Fx::pi() * 0.25_fx);
  const BodyId2D heavy = add(world, ball);
  ASSERT_TRUE(world.create_joint(revolute(previous, heavy, anchor)).ok());
  const double rigid_y = d(anchor.y) - 0.5;
  report("chain_ball mass_ratio", d(world.mass(heavy).to_fx()) / d(link_mass), "x");
  double worst = 0.0;
  for (int t = 0; t < 8 * kTicksPerSecond; ++t) {
    world.step();
    worst = std::max(worst, rigid_y - d(world.position(heavy).y));
  }
  const double stretch = rigid_y - d(world.position(heavy).y);
  report("chain_ball stretch_m", stretch, "m", "<=", 0.275);
  report("chain_ball worst_stretch_m", worst, "m", "<=", 0.55);
  report("chain_ball speed_mps", speed(world, heavy), "m/s", "<=", 0.1);
  EXPECT_LE(stretch, 0.275);
  EXPECT_LE(worst, 0.55);
  EXPECT_LE(speed(world, heavy), 0.1);
  expect_replays_bit_for_bit(world, 60);
}

// Box2D's joint grid: 100 x 100 circles (radius 0.4 m, 0.5 kg) 1 m apart,
// each pinned to its upper and left neighbours at the midpoint, hanging
// from the seven middle circles of the top row, at default settings. The
// grid falls and swings on those seven; the joints beside them carry up to
// 18 kN on 0.5 kg links, so the soft joints there open most at the bottom
// of each swing. Criterion: over 5 s no joint opens by more than 1 m (a
// grid's pitch; measured 0.44 m at the worst swing) and nothing moves
// faster than 25 m/s (measured 10 m/s). With the joints solved in the order
// they were made, the links beside the anchors spun up within 1.7 s and
// the grid came apart (joints 500 m open, links at 100 m/s).
TEST(Stability2D, HundredByHundredJointGridHangsTogether) {
  constexpr int kSide = 100;
  World2DConfig config;
  config.max_bodies = 2 * kSide * kSide + 16;  // joints share the capacity
  World2D world(config);
  std::vector<BodyId2D> grid;
  for (int k = 0; k < kSide; ++k) {
    for (int i = 0; i < kSide; ++i) {
      const bool anchor = i == 0 && k >= kSide / 2 - 3 && k <= kSide / 2 + 3;
      grid.push_back(add(world, def(make_circle(0.4_fx), {Fx(k), Fx(-i)}, Fx(),
                                    anchor ? BodyKind2D::kStatic : BodyKind2D::kDynamic)));
    }
  }
  struct Pin {
    BodyId2D a;
    BodyId2D b;
  };
  std::vector<Pin> pins;
  const auto at = [&](int k, int i) { return grid[static_cast<size_t>(k * kSide + i)]; };
  for (int k = 0; k < kSide; ++k) {
    for (int i = 0; i < kSide; ++i) {
      if (i > 0) {
        ASSERT_TRUE(
            world.create_joint(revolute(at(k, i - 1), at(k, i), {Fx(k), Fx(-i) + 0.5_fx})).ok());
        pins.push_back({at(k, i - 1), at(k, i)});
      }
      if (k > 0) {  // the anchors side by side too, as Box2D's grid
        ASSERT_TRUE(
            world.create_joint(revolute(at(k - 1, i), at(k, i), {Fx(k) - 0.5_fx, Fx(-i)})).ok());
        pins.push_back({at(k - 1, i), at(k, i)});
      }
    }
  }
  double widest = 0.0;
  double fastest = 0.0;
  for (int t = 0; t < 5 * kTicksPerSecond; ++t) {
    world.step();
    if (t % 10 != 9) continue;
    for (const Pin& p : pins) {
      widest = std::max(widest, d(fixed::length(world.position(p.b) - world.position(p.a))) - 1.0);
    }
    for (const BodyId2D b : grid) fastest = std::max(fastest, speed(world, b));
  }
  report("joint_grid widest_opening_m", widest, "m", "<=", 1.0);
  report("joint_grid fastest_mps", fastest, "m/s", "<=", 25.0);
  EXPECT_LE(widest, 1.0);
  EXPECT_LE(fastest, 25.0);
}

// A rope bridge: 30 planks (1 m, revolute-pinned end to end, a little
// angular damping as rope and wood have) hung with slack between two pins
// 29.07 m apart (the planks start in a shallow V), with 10 boxes dropped
// on it. Criterion: no joint ever opens by more than 5 cm, the bridge
// carries every box (none falls below its planks' lowest point, 6 m), and
// nothing moves faster than 15 m/s (the boxes fall 4.5 m at most: 9.5 m/s).
TEST(Stability2D, BridgeCarriesALoadWithoutComingApart) {
  World2D world;
  const fixed::SinCos tilt = fixed::sin_cos(0.25_fx);
  Vec2 at{-(tilt.cos * 15), Fx()};
  BodyId2D previous = add(world, def(make_circle(0.2_fx), at, Fx(), BodyKind2D::kStatic));
  std::vector<BodyId2D> planks;
  for (int i = 0; i < 30; ++i) {
    const bool down = i < 15;
    const Vec2 dir{tilt.cos, down ? -tilt.sin : tilt.sin};
    BodyDef2D plank = def(make_box(0.5_fx, 0.1_fx), at + dir * 0.5_fx, down ? -0.25_fx : 0.25_fx);
    plank.angular_damping = 0.5_fx;
    const BodyId2D id = add(world, plank);
    ASSERT_TRUE(world.create_joint(revolute(previous, id, at)).ok());
    planks.push_back(id);
    previous = id;
    at = at + dir;
  }
  const BodyId2D pin = add(world, def(make_circle(0.2_fx), at, Fx(), BodyKind2D::kStatic));
  ASSERT_TRUE(world.create_joint(revolute(previous, pin, at)).ok());
  std::vector<BodyId2D> loads;
  for (int i = 0; i < 10; ++i) {
    loads.push_back(add(world, def(make_box(0.4_fx, 0.4_fx), {Fx(i * 2 - 9), 1_fx + Fx(i % 3)})));
  }
  double worst_gap = 0.0;
  double lowest_load = 0.0;
  double fastest = 0.0;
  for (int t = 0; t < 8 * kTicksPerSecond; ++t) {
    world.step();
    for (size_t i = 0; i + 1 < planks.size(); ++i) {
      // Plank i's right end against plank i + 1's left end.
      const Vec2 end =
          world.position(planks[i]) + fixed::rotate(world.rotation(planks[i]), Vec2{0.5_fx, Fx()});
      const Vec2 start = world.position(planks[i + 1]) +
                         fixed::rotate(world.rotation(planks[i + 1]), Vec2{-0.5_fx, Fx()});
      worst_gap = std::max(worst_gap, d(fixed::length(end - start)));
    }
    for (const BodyId2D id : loads) {
      lowest_load = std::min(lowest_load, d(world.position(id).y));
      fastest = std::max(fastest, speed(world, id));
    }
    for (const BodyId2D id : planks) fastest = std::max(fastest, speed(world, id));
  }
  report("bridge worst_gap_m", worst_gap, "m", "<=", 0.05);
  report("bridge lowest_load_m", lowest_load, "m", ">=", -6.0);
  report("bridge fastest_mps", fastest, "m/s", "<=", 15.0);
  EXPECT_LE(worst_gap, 0.05);
  EXPECT_GE(lowest_load, -6.0);
  EXPECT_LE(fastest, 15.0);
  expect_replays_bit_for_bit(world, 60);
}

// Ten ragdolls (a torso, a head, two arms, two legs on limited revolute
// joints) dropped in a heap. Criterion: no joint ever opens by more than
// 10 cm (the impacts stretch the soft joints for a few ticks), nothing is
// ever faster than 20 m/s (the highest falls 13 m: 16 m/s), and by 10 s the
// heap has settled (every part slower than 0.5 m/s).
TEST(Stability2D, RagdollPileSettles) {
  World2D world;
  add_ground(world);
  struct Limb {
    BodyId2D body;
    Vec2 local;  // the joint in the limb's frame
    BodyId2D parent;
    Vec2 parent_local;
  };
  std::vector<Limb> limbs;
  std::vector<BodyId2D> all;
  for (int r = 0; r < 10; ++r) {
    const Vec2 hip{Fx((r % 3) - 1) * 0.3_fx, 2_fx + Fx(r) * 1.2_fx};
    const BodyId2D torso =
        add(world, def(make_capsule({Fx(), Fx()}, {Fx(), 0.6_fx}, 0.15_fx), hip));
    const BodyId2D head = add(world, def(make_circle(0.15_fx), hip + Vec2{Fx(), 0.9_fx}));
    all.push_back(torso);
    all.push_back(head);
    auto attach = [&](BodyId2D part, Vec2 at, Fx lower, Fx upper, Vec2 local, Vec2 parent_local) {
      JointDef2D j = revolute(torso, part, at);
      j.enable_limit = true;
      j.lower = lower;
      j.upper = upper;
      ASSERT_TRUE(world.create_joint(j).ok());
      limbs.push_back({part, local, torso, parent_local});
      all.push_back(part);
    };
    attach(head, hip + Vec2{Fx(), 0.75_fx}, -0.5_fx, 0.5_fx, {Fx(), -0.15_fx}, {Fx(), 0.75_fx});
    for (const Fx side : {-1_fx, 1_fx}) {
      const BodyId2D arm = add(world, def(make_capsule({Fx(), -0.5_fx}, {Fx(), Fx()}, 0.06_fx),
                                          hip + Vec2{side * 0.25_fx, 0.6_fx}));
      attach(arm, hip + Vec2{side * 0.25_fx, 0.6_fx}, -2_fx, 2_fx, {}, {side * 0.25_fx, 0.6_fx});
      const BodyId2D leg = add(world, def(make_capsule({Fx(), -0.7_fx}, {Fx(), Fx()}, 0.08_fx),
                                          hip + Vec2{side * 0.1_fx, -0.1_fx}));
      attach(leg, hip + Vec2{side * 0.1_fx, -0.1_fx}, -1_fx, 1_fx, {}, {side * 0.1_fx, -0.1_fx});
    }
  }
  double worst_gap = 0.0;
  double fastest = 0.0;
  double last_speed = 0.0;
  for (int t = 0; t < 10 * kTicksPerSecond; ++t) {
    world.step();
    for (const Limb& l : limbs) {
      const Vec2 a = world.position(l.body) + fixed::rotate(world.rotation(l.body), l.local);
      const Vec2 b =
          world.position(l.parent) + fixed::rotate(world.rotation(l.parent), l.parent_local);
      worst_gap = std::max(worst_gap, d(fixed::length(a - b)));
    }
    last_speed = 0.0;
    for (const BodyId2D id : all) {
      fastest = std::max(fastest, speed(world, id));
      last_speed = std::max(last_speed, speed(world, id));
    }
  }
  report("ragdolls worst_gap_m", worst_gap, "m", "<=", 0.1);
  report("ragdolls fastest_mps", fastest, "m/s", "<=", 20.0);
  report("ragdolls final_speed_mps", last_speed, "m/s", "<=", 0.5);
  EXPECT_LE(worst_gap, 0.1);
  EXPECT_LE(fastest, 20.0);
  EXPECT_LE(last_speed, 0.5);
  expect_replays_bit_for_bit(world, 30);
}

}  // namespace
}  // namespace rwd::sim2d
