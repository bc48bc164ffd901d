// SPDX-License-Identifier: MIT
#include "lane2d_scene.h"

#include <cinttypes>
#include <cstdio>
#include <vector>

#include "rewind/core/state_hasher.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/sim2d/chain2d.h"
#include "rewind/sim2d/character2d.h"
#include "rewind/sim2d/world2d.h"

namespace rwd::determinism {
namespace {

using fixed::Fx;
using fixed::Vec2;
using namespace fixed::literals;
using namespace sim2d;

BodyId2D add(World2D& world, BodyKind2D kind, const Result<Shape2D>& shape, Vec2 at,
             Fx angle = Fx()) {
  if (!shape.ok()) return {};
  BodyDef2D def;
  def.kind = kind;
  def.shape = *shape;
  def.position = at;
  def.angle = angle;
  def.material.restitution = Fx::ratio(1, 5);
  auto id = world.create_body(def);
  return id.ok() ? *id : BodyId2D{};
}

JointDef2D joint(JointType2D type, BodyId2D a, BodyId2D b, Vec2 at) {
  JointDef2D j;
  j.type = type;
  j.body_a = a;
  j.body_b = b;
  j.anchor_a = at;
  j.anchor_b = at;
  return j;
}

void build(World2D& world) {
  // A bumpy chain floor and two walls.
  const Vec2 floor_points[] = {{-20_fx, 2_fx}, {-12_fx, Fx()},  {-4_fx, 0.25_fx},
                               {4_fx, Fx()},   {12_fx, 0.5_fx}, {20_fx, 3_fx}};
  auto floor = make_chain(floor_points, false);
  if (floor.ok()) {
    for (const Shape2D& s : *floor) add(world, BodyKind2D::kStatic, s, {});
  }
  add(world, BodyKind2D::kStatic, make_box(0.5_fx, 10_fx), {-21_fx, 8_fx});
  add(world, BodyKind2D::kStatic, make_box(0.5_fx, 10_fx), {21_fx, 8_fx});
  // A small pyramid and a heap of mixed shapes falling onto it.
  for (int row = 0; row < 5; ++row) {
    for (int i = 0; i < 5 - row; ++i) {
      add(world, BodyKind2D::kDynamic, make_box(0.4_fx, 0.4_fx),
          {Fx(i - 2) + Fx(row) / 2 - 8_fx, 0.7_fx + Fx(row) * 0.8_fx});
    }
  }
  const Vec2 hexagon[] = {{0.4_fx, Fx()},  {0.2_fx, 0.35_fx},   {-0.2_fx, 0.35_fx},
                          {-0.4_fx, Fx()}, {-0.2_fx, -0.35_fx}, {0.2_fx, -0.35_fx}};
  for (int i = 0; i < 12; ++i) {
    const Vec2 at{Fx(i % 4) - 9.5_fx, 6_fx + Fx(i / 4) * 1.2_fx};
    const Fx angle = Fx::ratio(i, 7);
    if (i % 3 == 0) add(world, BodyKind2D::kDynamic, make_circle(0.3_fx), at);
    if (i % 3 == 1)
      add(world, BodyKind2D::kDynamic, make_capsule({-0.3_fx, Fx()}, {0.3_fx, Fx()}, 0.15_fx), at,
          angle);
    if (i % 3 == 2) add(world, BodyKind2D::kDynamic, make_polygon(hexagon, 0.05_fx), at, angle);
  }
  // Every joint type: a hanging chain of links (revolute), a rope
  // (distance range), a spring, a slider, a wheel, a weld, and a grab.
  const BodyId2D pin = add(world, BodyKind2D::kStatic, make_circle(0.1_fx), {4_fx, 9_fx});
  BodyId2D previous = pin;
  Vec2 at{4_fx, 9_fx};
  for (int i = 0; i < 5; ++i) {
    const BodyId2D link =
        add(world, BodyKind2D::kDynamic, make_box(0.4_fx, 0.08_fx), at + Vec2{0.4_fx, Fx()});
    JointDef2D j = joint(JointType2D::kRevolute, previous, link, at);
    if (i == 0) {
      j.enable_limit = true;
      j.lower = -1_fx;
      j.upper = 1_fx;
      j.enable_motor = true;
      j.motor_speed = 1_fx;
      j.max_motor = 5_fx;
    }
    (void)world.create_joint(j);
    previous = link;
    at = at + Vec2{0.8_fx, Fx()};
  }
  const BodyId2D weight =
      add(world, BodyKind2D::kDynamic, make_circle(0.3_fx), at + Vec2{Fx(), -1_fx});
  JointDef2D rope = joint(JointType2D::kDistance, previous, weight, at);
  rope.anchor_b = at + Vec2{Fx(), -1_fx};
  rope.min_length = Fx();
  rope.max_length = 1.5_fx;
  (void)world.create_joint(rope);
  const BodyId2D anchor = add(world, BodyKind2D::kStatic, make_circle(0.1_fx), {12_fx, 10_fx});
  const BodyId2D bob = add(world, BodyKind2D::kDynamic, make_box(0.3_fx, 0.3_fx), {13_fx, 8_fx});
  (void)world.create_joint(spring_joint(anchor, bob, {12_fx, 10_fx}, {13_fx, 8_fx}, 2_fx, 0.3_fx));
  const BodyId2D rail = add(world, BodyKind2D::kStatic, make_circle(0.1_fx), {15_fx, 6_fx});
  const BodyId2D slider = add(world, BodyKind2D::kDynamic, make_box(0.3_fx, 0.2_fx), {15_fx, 6_fx});
  JointDef2D slide = joint(JointType2D::kPrismatic, rail, slider, {15_fx, 6_fx});
  slide.axis = {1_fx, 1_fx};
  slide.enable_limit = true;
  slide.lower = -2_fx;
  slide.upper = 1_fx;
  (void)world.create_joint(slide);
  const BodyId2D cart = add(world, BodyKind2D::kDynamic, make_box(1_fx, 0.2_fx), {-14_fx, 4_fx});
  const BodyId2D wheel = add(world, BodyKind2D::kDynamic, make_circle(0.35_fx), {-14.7_fx, 3.4_fx});
  JointDef2D axle = joint(JointType2D::kWheel, cart, wheel, {-14.7_fx, 3.4_fx});
  axle.axis = {Fx(), 1_fx};
  axle.enable_motor = true;
  axle.motor_speed = -4_fx;
  axle.max_motor = 20_fx;
  (void)world.create_joint(axle);
  const BodyId2D plate =
      add(world, BodyKind2D::kDynamic, make_box(0.5_fx, 0.1_fx), {-13_fx, 4.4_fx});
  JointDef2D weld = joint(JointType2D::kWeld, cart, plate, {-13_fx, 4.3_fx});
  weld.angular_hertz = 5_fx;
  weld.damping_ratio = 0.5_fx;
  (void)world.create_joint(weld);
  JointDef2D grab = joint(JointType2D::kGrab, pin, bob, {13_fx, 8_fx});
  grab.target = {10_fx, 5_fx};
  grab.max_force = 50_fx;
  grab.break_impulse = 3_fx;
  (void)world.create_joint(grab);
  // A sensor zone over the middle.
  BodyDef2D zone;
  zone.kind = BodyKind2D::kStatic;
  zone.shape = *make_box(2_fx, 1_fx);
  zone.position = {Fx(), 1.5_fx};
  zone.sensor = true;
  (void)world.create_body(zone);
}

// Fires a continuous bullet across the scene.
void fire(World2D& world, int shot) {
  BodyDef2D bullet;
  bullet.shape = *make_circle(0.05_fx);
  bullet.position = {-19_fx, 1_fx + Fx(shot % 4)};
  bullet.linear_velocity = {300_fx, Fx(shot % 3 - 1) * 20};
  bullet.continuous = true;
  bullet.density = 20_fx;
  (void)world.create_body(bullet);
}

// Every query once, their results streamed into `hasher`.
void digest_queries(const World2D& world, int tick, rwd::StateHasher& hasher,
                    std::vector<RayHit2D>& hits, std::vector<BodyId2D>& bodies) {
  auto add_vec = [&](Vec2 v) {
    hasher.add_i32(v.x.raw());
    hasher.add_i32(v.y.raw());
  };
  const Vec2 origin{Fx(tick % 37) - 18_fx, 12_fx};
  world.raycast_all(origin, {Fx(tick % 5) - 2_fx, -14_fx}, {}, hits);
  hasher.add_u32(static_cast<uint32_t>(hits.size()));
  for (const RayHit2D& h : hits) {
    hasher.add_u32(h.body.index);
    add_vec(h.point);
    add_vec(h.normal);
    hasher.add_i32(h.fraction.raw());
  }
  world.query_aabb({-10_fx, Fx()}, {-6_fx, 4_fx}, {}, bodies);
  for (const BodyId2D b : bodies) hasher.add_u32(b.index);
  world.overlap(*make_circle(1_fx), {Fx(tick % 11) - 10_fx, 1_fx}, Fx(), {}, bodies);
  for (const BodyId2D b : bodies) hasher.add_u32(b.index);
  if (auto hit = world.shape_cast(*make_box(0.2_fx, 0.2_fx), {-5_fx, 8_fx}, Fx::ratio(tick, 50),
                                  {Fx(), -9_fx})) {
    hasher.add_u32(hit->body.index);
    hasher.add_i32(hit->fraction.raw());
    add_vec(hit->normal);
  }
  if (auto near = world.nearest_body({Fx(tick % 13) - 6_fx, 3_fx}, 5_fx)) {
    hasher.add_u32(near->body.index);
    hasher.add_i32(near->distance.raw());
  }
  hasher.add_i32(world.signed_distance({-8_fx, 1_fx}).raw());
}

}  // namespace

bool run_lane2d_scene(int ticks) {
  World2D world;
  build(world);
  CharacterState2D character;
  character.position = {2_fx, 2_fx};
  const CharacterConfig2D character_config;
  std::vector<RayHit2D> hits;
  std::vector<BodyId2D> bodies;
  World2DState saved;
  CharacterState2D saved_character;
  std::vector<uint64_t> first_pass;
  for (int t = 0; t < ticks; ++t) {
    if (t % 60 == 5) fire(world, t / 60);
    // The character walks back and forth under gravity.
    const Fx walk = (t / 90) % 2 == 0 ? 0.08_fx : -0.08_fx;
    character.velocity.y = character.grounded ? Fx() : character.velocity.y - Fx::ratio(1, 6);
    move_character(world, character, {walk, character.velocity.y / 60}, character_config);
    if (t % 30 == 0) {
      // Restore-and-re-step: the next 10 ticks twice.
      world.save(saved);
      saved_character = character;
      first_pass.clear();
      for (int i = 0; i < 10; ++i) {
        world.step();
        first_pass.push_back(world.checksum());
      }
      world.restore(saved);
      character = saved_character;
      for (int i = 0; i < 10; ++i) {
        world.step();
        if (world.checksum() != first_pass[static_cast<size_t>(i)]) {
          std::printf("lane2d ROLLBACK-MISMATCH %d\n", t + i);
          return false;
        }
      }
      world.restore(saved);
    }
    if (t % 50 == 0) {
      std::vector<uint8_t> bytes;
      world.serialize(bytes);
      World2D reloaded;
      if (!reloaded.deserialize(bytes).ok() || reloaded.checksum() != world.checksum()) {
        std::printf("lane2d RELOAD-MISMATCH %d\n", t);
        return false;
      }
      world = std::move(reloaded);
    }
    world.step();
    rwd::StateHasher queries;
    digest_queries(world, t, queries, hits, bodies);
    queries.add_i32(character.position.x.raw());
    queries.add_i32(character.position.y.raw());
    queries.add_u8(character.grounded ? 1 : 0);
    std::printf("lane2d %d %016" PRIx64 " %016" PRIx64 "\n", t, world.checksum(), queries.digest());
  }
  return true;
}

}  // namespace rwd::determinism
