// SPDX-License-Identifier: MIT
// The 3D character controller: collide-and-slide on World3D::shape_cast.
// As in the 2D lane, a move is split into a pass across the up axis and a
// pass along it, so walking speed does not leak into falling and landing
// on a slope does not slide the character down it.
//
// The casts sweep the capsule grown by the skin, so a move that stops at
// the first touch leaves the real capsule a skin away from the surface,
// measured along its normal whatever the angle of approach. (Stopping a
// real-size capsule a skin short along the move instead lets a grazing
// walk along a wall creep into it.) A grown capsule ends each stop
// touching, and a cast that starts touching reports that body at distance
// 0 whatever the direction, so the casts look past bodies they start on
// and leave (first_hit).
#include "rewind/sim/character3d.h"

#include <initializer_list>
#include <optional>
#include <vector>

#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

// Moves shorter than this (m) are done: well below the skin's resolution.
constexpr float kMinMove = 1e-5f;
// Longest move one call makes, m.
constexpr float kMaxMove = 1000.0f;
// A cast starting in touch with a body and heading out of it, or along
// it, by at least this (the cosine between the move and the body's
// normal: a slide along a surface is a few ulps off it) is not held back
// by that body.
constexpr float kLeaving = -1e-5f;
// Planes met in one pass whose normals are closer than this (the sine of
// the angle between them) are one plane: no crease between them.
constexpr float kParallel = 1e-3f;
constexpr int kMaxSlides = 8;
constexpr int kMaxLogged = 2 * kMaxSlides + 1;

struct Ctx {
  const World3D& world;
  const QueryFilter& filter;
  Shape shape;    // the capsule grown by the skin
  Quat rotation;  // takes the capsule's local y onto `up`
  Vec3 up;
  float radius = 0.0f;
  float step = 0.0f;
  float slope_cos = 0.0f;
  float skin = 0.0f;
  int slides = 4;
};

struct Log {
  bool wall = false;
  bool ceiling = false;
  int count = 0;
  Vec3 normals[kMaxLogged];  // every surface met, for the velocity clip

  void add(Vec3 n) {
    if (count < kMaxLogged) normals[count++] = n;
  }
};

float max_f(float a, float b) {
  return a > b ? a : b;
}
float min_f(float a, float b) {
  return a < b ? a : b;
}

bool walkable(const Ctx& c, Vec3 normal) {
  const float n_up = dot(normal, c.up);
  return n_up > 0.0f && n_up >= c.slope_cos;
}

bool tiny(Vec3 v) {
  return !(length_squared(v) >= kMinMove * kMinMove);
}

// Per-thread list for the rare cast that starts touching a body: kept
// between calls so a warm caller allocates nothing.
std::vector<ShapeCastHit>& touching_hits() {
  thread_local std::vector<ShapeCastHit> hits;
  return hits;
}

// The first body the capsule meets going from `pos` by `move`, skipping
// the bodies it starts out touching and is leaving (or sliding along). A
// cast the world refuses is a hit at distance 0 against the move.
bool first_hit(const Ctx& c, Vec3 pos, Vec3 move, ShapeCastHit& out) {
  std::optional<ShapeCastHit> hit;
  const Vec3 dir = normalize_or_zero(move);
  if (!c.world.shape_cast(c.shape, pos, c.rotation, move, c.filter, hit).ok()) {
    out = ShapeCastHit{BodyId{}, 0.0f, pos, -dir};
    return true;
  }
  if (hit && hit->distance == 0.0f && dot(hit->normal, dir) >= kLeaving) {
    hit.reset();
    std::vector<ShapeCastHit>& all = touching_hits();
    if (c.world.shape_cast_all(c.shape, pos, c.rotation, move, c.filter, all).ok()) {
      for (const ShapeCastHit& h : all) {
        if (h.distance == 0.0f && dot(h.normal, dir) >= kLeaving) continue;
        hit = h;
        break;
      }
    }
  }
  if (!hit) return false;
  out = *hit;
  return true;
}

// Where a move of `move` from `pos` ends: the whole move, or a skin short
// of the first surface in the way (reported in `hit`).
bool advance(const Ctx& c, Vec3& pos, Vec3 move, float& done, ShapeCastHit& hit) {
  const float len = length(move);
  const Vec3 dir = move * (1.0f / len);
  done = len;
  if (!first_hit(c, pos, move, hit)) {
    pos += move;
    return false;
  }
  done = min_f(max_f(hit.distance, 0.0f), len);
  pos += dir * done;
  return true;
}

// One pass of collide-and-slide from `pos` by `move`. `vertical`: landing
// on walkable ground ends the pass instead of sliding along it.
Vec3 slide(const Ctx& c, Vec3 pos, Vec3 move, bool vertical, Log& log) {
  const Vec3 wanted = move;
  Vec3 planes[kMaxSlides];
  int plane_count = 0;
  for (int i = 0; i < c.slides && !tiny(move); ++i) {
    float done = 0.0f;
    ShapeCastHit hit;
    if (!advance(c, pos, move, done, hit)) return pos;
    const float len = length(move);
    const Vec3 rest = move * ((len - done) / len);
    Vec3 n = hit.normal;
    const float n_up = dot(n, c.up);
    const float rest_up = dot(rest, c.up);
    const bool ground = walkable(c, n);
    if (!ground) {
      if (n_up < 0.0f && -n_up >= c.slope_cos) {
        log.ceiling = true;
      } else {
        log.wall = true;
      }
    }
    if (vertical && ground && rest_up <= 0.0f) {
      log.add(n);
      return pos;
    }
    Vec3 slid = rest - n * dot(rest, n);
    // A steep slope facing up must not carry the character up it: it acts
    // as a wall standing along `up`, its normal's part across `up`.
    if (!ground && n_up > 0.0f && dot(slid, c.up) > max_f(rest_up, 0.0f)) {
      n = normalize_or_zero(n - c.up * n_up);
      if (n == Vec3{}) {
        log.add(hit.normal);
        return pos;
      }
      slid = rest - n * dot(rest, n);
    }
    log.add(n);
    // Sliding into a plane met before: follow the crease the two planes
    // make; a third plane in the way of that is a corner, a stop.
    const float slid_len = length(slid);
    for (int j = 0; j < plane_count; ++j) {
      if (dot(slid, planes[j]) >= -kParallel * slid_len) continue;
      const Vec3 line = cross(planes[j], n);
      if (length(line) < kParallel) continue;  // the same plane again
      const Vec3 along = normalize_or_zero(line);
      slid = along * dot(rest, along);
      for (int k = 0; k < plane_count; ++k) {
        if (k != j && dot(slid, planes[k]) < -kParallel * length(slid)) return pos;
      }
      break;
    }
    // Sliding back against the wanted move (into a crease) is a stop.
    if (!(dot(slid, wanted) > 0.0f)) return pos;
    if (plane_count < kMaxSlides) planes[plane_count++] = n;
    move = slid;
  }
  return pos;
}

struct Step {
  Vec3 position;
  Log log;
  ShapeCastHit land;  // the ledge's top under the capsule
};

// Up by the step height, across, then down onto the ledge. A rounded
// bottom that has moved only a little past the ledge's edge would come
// down on that edge (a steep contact) and slide off, so the landing height
// is found first by a probe that goes a full radius across; the real move
// then comes down only to that height, which leaves the capsule resting
// over the edge, close enough to walk onto it.
bool step_up(const Ctx& c, Vec3 start, Vec3 across, Step& out) {
  ShapeCastHit rise;
  float lift = c.step;
  if (first_hit(c, start, c.up * c.step, rise)) lift = min_f(lift, rise.distance);
  if (lift < kMinMove) return false;
  const Vec3 top = start + c.up * lift;
  const float across_len = length(across);
  const Vec3 dir = across * (1.0f / across_len);
  Log probe_log;
  const Vec3 probe = slide(c, top, dir * max_f(across_len, c.radius + c.skin), false, probe_log);
  const float probe_up = dot(probe, c.up);
  const float probe_rise = probe_up - dot(start, c.up);
  ShapeCastHit land;
  if (probe_rise < kMinMove || !first_hit(c, probe, c.up * -probe_rise, land)) return false;
  if (!walkable(c, land.normal)) return false;
  // The height of the capsule's centre standing on the ledge.
  const float ledge_up = probe_up - land.distance;
  const float start_up = dot(start, c.up);
  if (ledge_up <= start_up + kMinMove) return false;          // no higher: not a step
  if (ledge_up > start_up + c.step + kMinMove) return false;  // too high
  Log side_log;
  Vec3 pos = slide(c, top, across, false, side_log);
  const float drop = dot(pos, c.up) - ledge_up;
  if (drop > kMinMove) {
    float done = 0.0f;
    ShapeCastHit stop;
    advance(c, pos, c.up * -drop, done, stop);
  }
  out.position = pos;
  out.log = side_log;
  out.log.add(land.normal);
  out.land = land;
  return true;
}

struct Ground {
  bool found = false;
  Vec3 position;
  ShapeCastHit hit;  // the walkable surface stood on
};

// The ground probe: first up by `lift` where there is room (out of ground
// that rose into the capsule), then down by that plus `reach`. Walkable
// ground found puts the capsule a skin above it. When the first surface
// met is steep (an edge the round bottom leans on, a wall's foot),
// walkable ground within a skin past it still holds the character; the
// capsule then comes down only to the first surface.
Ground probe_ground(const Ctx& c, Vec3 pos, float lift, float reach) {
  Ground g;
  ShapeCastHit room;
  if (first_hit(c, pos, c.up * lift, room)) lift = min_f(lift, room.distance);
  const Vec3 top = pos + c.up * lift;
  const Vec3 down = c.up * -(lift + reach);
  ShapeCastHit first;
  if (!first_hit(c, top, down, first)) return g;
  g.position = top - c.up * max_f(first.distance, 0.0f);
  if (walkable(c, first.normal)) {
    g.found = true;
    g.hit = first;
    return g;
  }
  std::vector<ShapeCastHit>& all = touching_hits();
  if (!c.world.shape_cast_all(c.shape, top, c.rotation, down, c.filter, all).ok()) return g;
  for (const ShapeCastHit& h : all) {
    if (h.distance > first.distance + c.skin) break;
    if (h.distance == 0.0f && -dot(h.normal, c.up) >= kLeaving) continue;
    if (walkable(c, h.normal)) {
      g.found = true;
      g.hit = h;
      break;
    }
  }
  return g;
}

float clamp_or(float v, float lo, float hi, float fallback) {
  if (!is_finite(v)) return fallback;
  return v < lo ? lo : (v > hi ? hi : v);
}

// The rotation taking +y onto the unit vector u (the half-way quaternion).
Quat rotation_to(Vec3 u) {
  const float w = 1.0f + u.y;
  if (w < 1e-6f) return Quat{1.0f, 0.0f, 0.0f, 0.0f};  // u = -y: half a turn about x
  return normalize(Quat{u.z, 0.0f, -u.x, w});
}

Vec3 finite_or_zero(Vec3 v) {
  return is_finite(v) ? v : Vec3{};
}

}  // namespace

CharacterMove3D move_character(const World3D& world, CharacterState3D& state, Vec3 desired,
                               const CharacterConfig3D& config, const QueryFilter& filter) {
  CharacterMove3D result;
  if (!is_finite(state.position)) return result;
  const CharacterConfig3D defaults;
  Vec3 up = is_finite(config.up) ? normalize_or_zero(config.up) : Vec3{};
  if (up == Vec3{}) up = defaults.up;
  const float radius = clamp_or(config.radius, 1.0f / 256.0f, 10.0f, defaults.radius);
  const float half_height = clamp_or(config.half_height, 0.0f, 10.0f, defaults.half_height);
  const int slides = config.max_slides < 1 ? 1 : (config.max_slides > 8 ? 8 : config.max_slides);
  const float skin = clamp_or(config.skin, 1.0f / 4096.0f, 1.0f, defaults.skin);
  const Ctx c{world,
              filter,
              half_height > 0.0f ? Shape::make_capsule(radius + skin, half_height)
                                 : Shape::make_sphere(radius + skin),
              rotation_to(up),
              up,
              radius,
              clamp_or(config.step_height, 0.0f, 10.0f, defaults.step_height),
              clamp_or(config.max_slope_cos, 0.0f, 1.0f, defaults.max_slope_cos),
              skin,
              slides};

  Vec3 d = finite_or_zero(desired);
  const float d_len = length(d);
  if (d_len > kMaxMove) d = d * (kMaxMove / d_len);
  const float d_up = dot(d, up);
  const Vec3 d_across = d - up * d_up;
  const Vec3 start = state.position;

  // Across, and up a ledge when that gets further along.
  Log side_log;
  Vec3 pos = tiny(d_across) ? start : slide(c, start, d_across, false, side_log);
  Step step;
  if (state.grounded && side_log.wall && c.step > 0.0f && !tiny(d_across) &&
      step_up(c, start, d_across, step) &&
      dot(step.position - start, d_across) > dot(pos - start, d_across) + kMinMove * d_len) {
    pos = step.position;
    side_log = step.log;
    result.stepped_up = true;
  }

  // Along up. After a step the capsule already came down onto the ledge.
  Log vertical_log;
  if (!(result.stepped_up && d_up <= 0.0f) && !tiny(up * d_up)) {
    pos = slide(c, pos, up * d_up, true, vertical_log);
  }

  // The ground probe: a skin's reach, or a step's when the character was
  // standing and is not jumping, so it follows slopes and steps down.
  const bool follow = state.grounded && d_up <= 0.0f;
  const float reach = follow ? max_f(c.step, 2.0f * c.skin) : 2.0f * c.skin;
  const Ground ground = probe_ground(c, pos, max_f(2.0f * c.skin, 0.5f * c.radius), reach);
  bool grounded = ground.found;
  Vec3 ground_normal;
  BodyId ground_body;
  if (grounded) {
    pos = ground.position;
    ground_normal = ground.hit.normal;
    ground_body = ground.hit.body;
  } else if (result.stepped_up) {
    // Resting over the ledge's edge: it stands on the ledge it landed on.
    grounded = true;
    ground_normal = step.land.normal;
    ground_body = step.land.body;
  }

  // The velocity keeps only what does not press into a surface met.
  Vec3 v = finite_or_zero(state.velocity);
  for (const Log* log : {&side_log, &vertical_log}) {
    for (int i = 0; i < log->count; ++i) {
      const Vec3 n = log->normals[i];
      if (walkable(c, n)) {
        const float fall = dot(v, up);
        if (fall < 0.0f) v = v - up * fall;
        continue;
      }
      const float into = dot(v, n);
      if (into < 0.0f) v = v - n * into;
    }
  }
  if (grounded) {
    const float fall = dot(v, up);
    if (fall < 0.0f) v = v - up * fall;
  }

  // Far outside any sane world the arithmetic could overflow: then nothing moves.
  if (!is_finite(pos) || !is_finite(v) || !is_finite(ground_normal)) {
    pos = start;
    v = Vec3{};
    grounded = false;
    ground_normal = Vec3{};
    ground_body = BodyId{};
  }
  result.translation = pos - start;
  result.hit_wall = side_log.wall || vertical_log.wall;
  result.hit_ceiling = vertical_log.ceiling;
  state.position = pos;
  state.velocity = v;
  state.grounded = grounded;
  state.ground_normal = grounded ? ground_normal : Vec3{};
  state.ground = grounded ? ground_body : BodyId{};
  return result;
}

}  // namespace rwd::sim
