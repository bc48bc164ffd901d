// SPDX-License-Identifier: MIT
// The 2D character controller: collide-and-slide on shape casts. Moves are
// split into a sideways and a vertical pass, as most platformer
// controllers do, so walking speed does not leak into falling and landing
// on a slope does not slide the character down it.
#include "rewind/sim2d/character2d.h"

#include <initializer_list>

#include "distance2d.h"
#include "rewind/sim2d/world2d.h"
#include "shape_cast2d.h"
#include "wmath.h"

namespace rwd::sim2d {

using namespace detail;

namespace {

// Moves shorter than this (m) are done: below the skin's resolution.
constexpr W kMinMove = W{1} << 8;  // 2^-24 m

struct Ctx {
  const World2D& world;
  const World2DState& state;
  QueryFilter2D filter;
  W radius = 0;
  W half_height = 0;
  W step = 0;
  W slope_cos = 0;
  W skin = 0;
  int slides = 4;
};

struct Log {
  bool wall = false;
  bool ceiling = false;
  bool ground = false;
  int count = 0;
  V2 normals[16];  // every surface met, for the velocity clip
};

WPoly capsule_at(const Ctx& c, V2 p) {
  WPoly core;
  core.radius = c.radius;
  if (c.half_height == 0) {
    core.count = 1;
    core.vertices[0] = p;
    return core;
  }
  core.count = 2;
  core.vertices[0] = {p.x, p.y - c.half_height};
  core.vertices[1] = {p.x, p.y + c.half_height};
  core.normals[0] = {kWOne, 0};
  core.normals[1] = {-kWOne, 0};
  return core;
}

bool tiny(V2 v) {
  return wabs(v.x) < kMinMove && wabs(v.y) < kMinMove;
}

V2 scaled(W t, V2 v) {
  return {wmul(t, v.x), wmul(t, v.y)};
}

// One pass of collide-and-slide from `pos` by `move`. `vertical`: landing
// on walkable ground ends the pass instead of sliding along it.
V2 slide(const Ctx& c, V2 pos, V2 move, bool vertical, Log& log) {
  const V2 wanted = move;
  for (int i = 0; i < c.slides && !tiny(move); ++i) {
    CastResult2 hit;
    if (!cast_core(c.world, c.filter, capsule_at(c, pos), move, c.skin, hit)) {
      return pos + move;
    }
    const V2 done = scaled(hit.fraction, move);
    pos += done;
    V2 rest = move - done;
    const V2 n = hit.normal;
    if (log.count < 16) log.normals[log.count++] = n;
    const bool walkable = n.y > 0 && n.y >= c.slope_cos;
    if (walkable) {
      log.ground = true;
    } else if (-n.y >= c.slope_cos) {
      log.ceiling = true;
    } else {
      log.wall = true;
    }
    if (vertical && walkable && rest.y <= 0) return pos;
    V2 slid = vmul_sub(rest, vdot(rest, n), n);
    // A steep slope facing up must not carry the character up it: it acts
    // as a vertical wall, keeping only the vertical part of the move.
    if (!walkable && n.y > 0 && slid.y > wmax(rest.y, 0)) slid = {0, rest.y};
    // Sliding back against the wanted move (into a crease) is a stop.
    if (vdot(slid, wanted) <= 0) return pos;
    move = slid;
  }
  return pos;
}

struct Probe {
  bool hit = false;
  W fraction = 0;
  V2 normal;
  uint32_t index = 0;
};

Probe cast(const Ctx& c, V2 pos, V2 move) {
  Probe p;
  CastResult2 r;
  if (tiny(move) || !cast_core(c.world, c.filter, capsule_at(c, pos), move, c.skin, r)) return p;
  return {true, r.fraction, r.normal, r.index};
}

// Up by the step height, sideways, then down onto the ledge. A rounded
// bottom that has moved only a little past the ledge's face would come down
// on its corner (a steep contact) and slide off, so the landing height is
// found first by a probe that goes a full radius across; the real move
// then comes down only to that height, which leaves the capsule resting
// over the corner, close enough to walk onto it.
bool step_up(const Ctx& c, V2 start, W dx, V2& out, Log& log) {
  const V2 up{0, c.step};
  const Probe rise = cast(c, start, up);
  const V2 top = start + (rise.hit ? scaled(rise.fraction, up) : up);
  const W lift = top.y - start.y;
  if (lift < kMinMove) return false;
  const W reach = c.radius + c.skin;
  Log probe_log;
  const V2 probe =
      slide(c, top, {dx < 0 ? -wmax(-dx, reach) : wmax(dx, reach), 0}, false, probe_log);
  const V2 down{0, -lift};
  const Probe land = cast(c, probe, down);
  if (!land.hit || land.normal.y < c.slope_cos) return false;
  const W floor_y = probe.y - wmul(land.fraction, lift);
  if (floor_y <= start.y + kMinMove) return false;  // no higher than before: not a step

  Log side_log;
  const V2 across = slide(c, top, {dx, 0}, false, side_log);
  const V2 settle{0, wmin(floor_y - across.y, 0)};
  const Probe stop = cast(c, across, settle);
  out = across + (stop.hit ? scaled(stop.fraction, settle) : settle);
  log = side_log;
  if (log.count < 16) log.normals[log.count++] = land.normal;
  return true;
}

W clamp_fx(Fx v, Fx lo, Fx hi) {
  return w_from(v < lo ? lo : (hi < v ? hi : v));
}

}  // namespace

CharacterMove2D move_character(const World2D& world, CharacterState2D& state, Vec2 desired,
                               const CharacterConfig2D& config, const QueryFilter2D& filter) {
  const Ctx c{world,
              world.state(),
              filter,
              clamp_fx(config.radius, Fx::from_raw(256), 10_fx),
              clamp_fx(config.half_height, Fx(), 10_fx),
              clamp_fx(config.step_height, Fx(), 10_fx),
              clamp_fx(config.max_slope_cos, Fx(), 1_fx),
              clamp_fx(config.skin, Fx::from_raw(16), 1_fx),
              config.max_slides < 1 ? 1 : (config.max_slides > 8 ? 8 : config.max_slides)};
  const V2 start = v_from(state.position);
  const V2 d = v_from(desired);
  CharacterMove2D result;

  // Sideways, and up a ledge when that gets further along.
  Log side_log;
  V2 pos = slide(c, start, {d.x, 0}, false, side_log);
  if (state.grounded && side_log.wall && c.step > 0) {
    V2 stepped;
    Log step_log;
    if (step_up(c, start, d.x, stepped, step_log) &&
        wabs(stepped.x - start.x) > wabs(pos.x - start.x) + kMinMove) {
      pos = stepped;
      side_log = step_log;
      result.stepped_up = true;
    }
  }

  // Vertically.
  Log vertical_log;
  pos = slide(c, pos, {0, d.y}, true, vertical_log);

  // The ground probe: a skin's reach, or a step's when the character was
  // standing and is not jumping, so it follows slopes and steps down.
  const W reach = (state.grounded && d.y <= 0) ? wmax(c.step, 2 * c.skin) : 2 * c.skin;
  const Probe ground = cast(c, pos, {0, -reach});
  const bool grounded = ground.hit && ground.normal.y >= c.slope_cos;
  if (grounded) pos.y -= wmul(ground.fraction, reach);

  // The velocity keeps only what does not press into a surface met.
  V2 v = v_from(state.velocity);
  for (const Log* log : {&side_log, &vertical_log}) {
    for (int i = 0; i < log->count; ++i) {
      const V2 n = log->normals[i];
      if (n.y >= c.slope_cos) {
        if (v.y < 0) v.y = 0;
        continue;
      }
      const W into = vdot(v, n);
      if (into < 0) v = vmul_sub(v, into, n);
    }
  }
  if (grounded && v.y < 0) v.y = 0;

  result.translation = v_to_fx(pos - start);
  result.hit_wall = side_log.wall || vertical_log.wall;
  result.hit_ceiling = vertical_log.ceiling;
  state.position = v_to_fx(pos);
  state.velocity = v_to_fx(v);
  state.grounded = grounded;
  state.ground_normal = grounded ? v_to_fx(ground.normal) : Vec2{};
  state.ground =
      grounded ? BodyId2D{ground.index, c.state.bodies[ground.index].generation} : BodyId2D{};
  return result;
}

}  // namespace rwd::sim2d
