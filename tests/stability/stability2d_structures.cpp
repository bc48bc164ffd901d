// SPDX-License-Identifier: MIT
// 2D lane stability: structures that stand by friction (two houses of
// cards, a masonry arch) and a row of dominoes that must fall in order, at
// default settings. Each scene also replays a stretch from a mid-scene save
// bit for bit. The bridge, the ragdoll pile and the chain holding a ball
// 100 times heavier than a link wait for joints, which the lane does not
// have yet.
#include "scene2d.h"

namespace rwd::sim2d {
namespace {

using namespace scene;  // NOLINT: test brevity

// Steps `world` 600 ticks (10 s at 60 Hz) and returns how far any of
// `bodies` moved from its start; a save at tick 300, restored, must replay
// 30 ticks bit for bit.
double drift_over_ten_seconds(World2D& world, const std::vector<BodyId2D>& bodies) {
  Drift drift;
  for (BodyId2D id : bodies) drift.track(world, id);
  World2DState mid;
  for (int t = 1; t <= 600; ++t) {
    world.step();
    drift.observe(world);
    if (t == 300) world.save(mid);
  }
  world.restore(mid);
  expect_replays_bit_for_bit(world, 30);
  return drift.max_move_m();
}

/// The card house of the 3D catalogue in 2D: `levels` frames wide at the
/// base, each frame two 2 cm x 1 m cards leaning 25 degrees off vertical
/// against each other, a flat 1.2 m card bridging neighbouring frames, the
/// next level's frames on those. Half a millimetre between touching faces.
std::vector<BodyId2D> build_card_house(World2D& world, int levels, Fx friction) {
  const Fx card_hx = 0.01_fx;
  const Fx card_hy = 0.5_fx;
  const Fx flat_hx = 0.6_fx;
  const Fx flat_hy = 0.01_fx;
  const Fx gap = 0.0005_fx;
  const Fx pitch = 0.95_fx;  // apex to apex
  const Fx tilt = fx_deg(25);
  const fixed::SinCos sc = fixed::sin_cos(tilt);
  std::vector<BodyId2D> cards;
  Fx base_y;
  for (int level = 0; level < levels; ++level) {
    const int frames = levels - level;
    const Fx first = -pitch * (frames - 1) / 2;
    Fx apex_y;
    for (int f = 0; f < frames; ++f) {
      const Fx apex_x = first + pitch * f;
      for (int side : {-1, 1}) {
        // The card's top outer corner meets the apex; its lowest corner is
        // just above the floor it stands on.
        const Vec2 c{apex_x + (card_hy * sc.sin + card_hx * sc.cos + gap) * side,
                     base_y + card_hy * sc.cos + card_hx * sc.sin + gap};
        BodyDef2D card = def(make_box(card_hx, card_hy), c, tilt * side);
        card.material.friction = friction;
        cards.push_back(add(world, card));
        apex_y = c.y + card_hy * sc.cos + card_hx * sc.sin;
      }
    }
    if (frames == 1) break;
    const Fx flat_y = apex_y + flat_hy + gap;
    for (int f = 0; f + 1 < frames; ++f) {
      BodyDef2D flat = def(make_box(flat_hx, flat_hy), {first + pitch * f + pitch / 2, flat_y});
      flat.material.friction = friction;
      cards.push_back(add(world, flat));
    }
    base_y = flat_y + flat_hy;
  }
  return cards;
}

// A 3-level card house (15 cards) with friction 0.6 stands 10 s: every card
// within 5 cm of its start (the 3D catalogue's bound). A leaning card needs
// mu of at least tan(25 deg) / 2 = 0.23 at its foot (more under the cards
// above), so with friction 0 the same house must fall: some card moves
// more than 0.2 m. Without that half the first could pass on a scene that
// stands for some other reason.
TEST(Stability2D, CardHouseStandsByFriction) {
  World2D world;
  add_ground(world, 0.6_fx);
  const std::vector<BodyId2D> cards = build_card_house(world, 3, 0.6_fx);
  ASSERT_EQ(cards.size(), 15u);
  const double moved = drift_over_ten_seconds(world, cards);
  report("card_house3 drift_m", moved, "m", "<=", 0.05);
  EXPECT_LE(moved, 0.05);

  World2D slippery;
  add_ground(slippery, Fx());
  Drift fall;
  for (BodyId2D id : build_card_house(slippery, 3, Fx())) fall.track(slippery, id);
  for (int t = 1; t <= 600; ++t) {
    slippery.step();
    fall.observe(slippery);
  }
  report("card_house3_mu0 drift_m", fall.max_move_m(), "m", ">=", 0.2);
  EXPECT_GE(fall.max_move_m(), 0.2);
}

/// Box2D v3's "Card House" sample (from PEEL), in its units: cards 2 mm x
/// 40 cm, 5 frames at the base. A frame is two cards 17.5 cm apart at their
/// centres, turned 25 degrees towards each other so their tops nearly meet;
/// a flat card lies across the tops of each two neighbouring frames; each
/// row stands 37 cm above the one below, shifted half a frame. The cards
/// start a millimetre into the ground and a few millimetres apart where
/// they meet, so the house first settles by that much. 40 cards, made row
/// by row from the left as the sample makes them.
std::vector<BodyId2D> build_box2d_card_house(World2D& world, Fx friction) {
  const Fx card_hx = 0.001_fx;
  const Fx card_hy = 0.2_fx;
  const Fx step = 0.175_fx;  // between the centres of the two cards of a frame
  std::vector<BodyId2D> cards;
  Fx row_x;
  Fx y = card_hy - 0.02_fx;
  for (int frames = 5; frames > 0; --frames) {
    Fx x = row_x;
    for (int f = 0; f < frames; ++f) {
      if (f != frames - 1) {
        BodyDef2D flat =
            def(make_box(card_hx, card_hy), {x + 0.25_fx, y + card_hy - 0.015_fx}, fx_deg(90));
        flat.material.friction = friction;
        cards.push_back(add(world, flat));
      }
      for (int side : {-1, 1}) {
        BodyDef2D card = def(make_box(card_hx, card_hy), {x, y}, fx_deg(25) * side);
        card.material.friction = friction;
        cards.push_back(add(world, card));
        x += step;
      }
    }
    y += card_hy * 2 - 0.03_fx;
    row_x += step;
  }
  return cards;
}

/// The sample's ground: a static box 80 m x 4 m whose top is y = 0.
void add_box2d_ground(World2D& world, Fx friction) {
  BodyDef2D g = def(make_box(40_fx, 2_fx), {Fx(), -2_fx}, Fx(), BodyKind2D::kStatic);
  g.material.friction = friction;
  add(world, g);
}

// Box2D's card house with the sample's friction (0.7) at default settings
// stands 10 s: every card within 5 cm of its start (settling closes the
// gaps it starts with: 3.4 cm at the top here, 3.8 cm in Box2D v3). With
// friction 0 the feet slide out and it must fall: some card moves more
// than 0.2 m.
TEST(Stability2D, Box2DCardHouseStandsByFriction) {
  World2D world;
  add_box2d_ground(world, 0.7_fx);
  const std::vector<BodyId2D> cards = build_box2d_card_house(world, 0.7_fx);
  ASSERT_EQ(cards.size(), 40u);
  const double moved = drift_over_ten_seconds(world, cards);
  report("box2d_card_house drift_m", moved, "m", "<=", 0.05);
  EXPECT_LE(moved, 0.05);

  World2D slippery;
  add_box2d_ground(slippery, Fx());
  Drift fall;
  for (BodyId2D id : build_box2d_card_house(slippery, Fx())) fall.track(slippery, id);
  for (int t = 1; t <= 600; ++t) {
    slippery.step();
    fall.observe(slippery);
  }
  report("box2d_card_house_mu0 drift_m", fall.max_move_m(), "m", ">=", 0.2);
  EXPECT_GE(fall.max_move_m(), 0.2);
}

/// A semicircular arch of 9 voussoirs (20 degrees each), inner radius 2 m,
/// outer 2.8 m, its feet on the ground at y = 0. The joints are radial and
/// the stones touch exactly (shared corners; the right half mirrored to the
/// left so the keystone is symmetric).
std::vector<BodyId2D> build_arch(World2D& world, Fx friction) {
  const Fx inner = 2_fx;
  const Fx outer = 2.8_fx;
  // Joint directions at 0, 20, ..., 80 degrees, mirrored for 100..180.
  std::vector<Vec2> dir;
  for (int k = 0; k <= 4; ++k) {
    const fixed::SinCos sc = fixed::sin_cos(fx_deg(20 * k));
    dir.push_back({k == 0 ? 1_fx : sc.cos, k == 0 ? Fx() : sc.sin});
  }
  for (int k = 4; k >= 0; --k)
    dir.push_back({-dir[static_cast<size_t>(k)].x, dir[static_cast<size_t>(k)].y});
  std::vector<BodyId2D> stones;
  for (size_t j = 0; j + 1 < dir.size(); ++j) {
    const Vec2 a = dir[j];
    const Vec2 b = dir[j + 1];
    const std::array<Vec2, 4> world_pts = {a * inner, a * outer, b * outer, b * inner};
    // The body sits at the mean of its corners (near its centroid), so its
    // origin and centre of mass nearly coincide.
    const Vec2 centre{(world_pts[0].x + world_pts[1].x + world_pts[2].x + world_pts[3].x) / 4,
                      (world_pts[0].y + world_pts[1].y + world_pts[2].y + world_pts[3].y) / 4};
    std::array<Vec2, 4> local;
    for (size_t i = 0; i < 4; ++i) local[i] = world_pts[i] - centre;
    BodyDef2D stone = def(make_polygon(local), centre);
    stone.material.friction = friction;
    stones.push_back(add(world, stone));
  }
  return stones;
}

// The arch stands on friction alone: with mu = 0.6 every stone stays within
// 2 cm of its start for 10 s (its joints may settle by a few slops, never
// open or slide). With mu = 0 the radial joints and the outward thrust at
// the feet cannot be held by normal forces alone, so the keystone must
// drop more than 0.5 m within the 10 s.
TEST(Stability2D, ArchHoldsWithFrictionAndFallsWithout) {
  World2D world;
  add_ground(world, 0.6_fx);
  const std::vector<BodyId2D> stones = build_arch(world, 0.6_fx);
  ASSERT_EQ(stones.size(), 9u);
  const double moved = drift_over_ten_seconds(world, stones);
  report("arch_mu0.6 max_move_m", moved, "m", "<=", 0.02);
  EXPECT_LE(moved, 0.02);

  World2D slippery;
  add_ground(slippery, Fx());
  const std::vector<BodyId2D> loose = build_arch(slippery, Fx());
  const BodyId2D key = loose[4];
  const double key_start = d(slippery.center_of_mass(key).y);
  double key_drop = 0.0;
  for (int t = 1; t <= 600; ++t) {
    slippery.step();
    key_drop = std::max(key_drop, key_start - d(slippery.center_of_mass(key).y));
  }
  report("arch_mu0 keystone_drop_m", key_drop, "m", ">=", 0.5);
  EXPECT_GE(key_drop, 0.5);
}

// Box2D's "double domino": 15 dominoes 0.25 m x 1 m standing 1 m apart (as
// far apart as they are tall, so each one ends lying flat under the next),
// the first pushed at its top with 0.2 N s. They must fall in order (each
// tips past 15 degrees strictly after the one before it), none may pass
// through its neighbour (centres stay in order along x; none turns past
// lying flat, 90 + 3 degrees), every one must end lying flat (within 3
// degrees) and in the last second of 15 s every point moves slower than
// 0.05 m/s.
TEST(Stability2D, DoubleDominoFallsInOrderAndLiesFlat) {
  constexpr int kCount = 15;
  World2D world;
  add_ground(world);
  std::vector<BodyId2D> dominoes;
  for (int i = 0; i < kCount; ++i) {
    dominoes.push_back(add(world, def(make_box(0.125_fx, 0.5_fx), {Fx(i) - 7.5_fx, 0.5_fx})));
  }
  ASSERT_TRUE(world.apply_linear_impulse(dominoes[0], {0.2_fx, Fx()}, {-7.5_fx, 1_fx}).ok());
  std::vector<int> tipped(kCount, -1);
  bool ordered = true;
  double most_turned = 0.0;
  double late_speed = 0.0;
  World2DState mid;
  for (int t = 1; t <= 900; ++t) {
    world.step();
    for (size_t i = 0; i < dominoes.size(); ++i) {
      const double a = std::fabs(d(world.angle(dominoes[i])));
      most_turned = std::max(most_turned, a);
      if (tipped[i] < 0 && a > deg(15)) tipped[i] = t;
      if (i + 1 < dominoes.size() &&
          world.center_of_mass(dominoes[i]).x >= world.center_of_mass(dominoes[i + 1]).x) {
        ordered = false;
      }
      if (t > 840) late_speed = std::max(late_speed, point_speed(world, dominoes[i], 0.52));
    }
    if (t == 240) world.save(mid);
  }
  bool in_order = tipped[0] > 0;
  for (size_t i = 1; i < tipped.size(); ++i) in_order = in_order && tipped[i] > tipped[i - 1];
  double flat_error = 0.0;
  for (BodyId2D id : dominoes) {
    flat_error = std::max(flat_error, std::fabs(std::fabs(d(world.angle(id))) - deg(90)));
  }
  constexpr double kDeg = 180.0 / 3.14159265358979323846;
  report("double_domino15 last_tip_s", tipped.back() * kTickS, "s", ">", 0);
  report("double_domino15 most_turned_deg", most_turned * kDeg, "deg", "<=", 93);
  report("double_domino15 flat_error_deg", flat_error * kDeg, "deg", "<=", 3);
  report("double_domino15 last_second_speed_mps", late_speed, "m/s", "<=", kRestSpeedMps);
  EXPECT_TRUE(in_order) << "tip ticks: first " << tipped[0] << ", last " << tipped.back();
  EXPECT_TRUE(ordered);
  EXPECT_LE(most_turned, deg(93));
  EXPECT_LE(flat_error, deg(3));
  EXPECT_LE(late_speed, kRestSpeedMps);
  world.restore(mid);
  expect_replays_bit_for_bit(world, 30);
}

// Two 1 m boxes half inside each other, no gravity: once apart (no contact
// for a second) they must be at rest, relative speed under 0.05 m/s.
TEST(Stability2D, PushOutLeavesNoVelocity) {
  World2DConfig config;
  config.gravity = {};
  World2D world(config);
  const BodyId2D a = add(world, def(make_box(0.5_fx, 0.5_fx), {Fx(), Fx()}));
  const BodyId2D b = add(world, def(make_box(0.5_fx, 0.5_fx), {0.5_fx, Fx()}));
  for (int t = 1; t <= 120; ++t) world.step();
  EXPECT_TRUE(world.events().empty());
  const double apart = d(world.linear_velocity(b).x) - d(world.linear_velocity(a).x);
  report("push_out relative_speed_mps", apart, "m/s", "<=", kRestSpeedMps);
  EXPECT_LE(std::fabs(apart), kRestSpeedMps);
}

}  // namespace
}  // namespace rwd::sim2d
