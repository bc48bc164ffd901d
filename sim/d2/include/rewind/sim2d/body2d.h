// SPDX-License-Identifier: MIT
#pragma once
// Bodies of the 2D lane: handles, kinds and the definition a body is made
// from. Public values are Q16.16 (Fx) in metres, seconds, kilograms and
// radians; the world keeps them in Q32.32 inside.
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/vec2.h"
#include "rewind/sim2d/shape2d.h"

namespace rwd::sim2d {

using namespace rwd::fixed::literals;

/// Handle to a body: its slot and the slot's generation (0 is the null
/// handle). Slots are taken lowest-free-first, so the same calls give the
/// same ids on every machine, and every order that affects results (pairs,
/// contacts, solver order) derives from `index`.
struct BodyId2D {
  uint32_t index = 0;
  uint32_t generation = 0;
  bool is_null() const { return generation == 0; }
  friend bool operator==(BodyId2D, BodyId2D) = default;
};

enum class BodyKind2D : uint8_t {
  kStatic = 0,     ///< never moves: walls, ground, level geometry
  kKinematic = 1,  ///< moves by the velocity you give it; pushes, is never pushed
  kDynamic = 2,    ///< moved by gravity, contacts, forces and impulses
};

/// Surface response. Per contact: friction is the geometric mean of the two
/// bodies', restitution and rolling resistance the larger of the two.
struct Material2D {
  Fx friction = 0.6_fx;          ///< Coulomb coefficient, [0, 10]
  Fx restitution = Fx();         ///< bounce, [0, 1]
  Fx rolling_resistance = Fx();  ///< [0, 1]; resists rolling by this x normal force x lever
};

/// Everything a body is made from. create_body() validates every field and
/// refuses the whole definition, changing nothing, if one is out of range.
struct BodyDef2D {
  BodyKind2D kind = BodyKind2D::kDynamic;
  Shape2D shape;         ///< from the shape2d.h factories; default: none (refused)
  Vec2 position;         ///< m, the body origin (where the shape's (0, 0) is)
  Fx angle;              ///< rad, counter-clockwise
  Vec2 linear_velocity;  ///< m/s of the centre of mass
  Fx angular_velocity;   ///< rad/s, counter-clockwise
  /// Drawing/layering depth: carried in state and the checksum, never
  /// collided on (bodies on every z meet).
  Fx z;
  Fx density = 1_fx;          ///< kg/m^2, (0, 30000]; dynamic bodies only
  Fx linear_damping = Fx();   ///< 1/s, [0, 1000]
  Fx angular_damping = Fx();  ///< 1/s, [0, 1000]
  Fx gravity_scale = 1_fx;    ///< multiplies world gravity, [-100, 100]
  Material2D material;
  uint32_t layer = 1;           ///< collision layer bits this body is on
  uint32_t mask = 0xFFFFFFFFu;  ///< layers it collides with (both sides must agree)
  /// Reports overlaps as events, never pushes or is pushed.
  bool sensor = false;
  /// A trigger is solid (it pushes and is pushed like any body) and its
  /// contacts' events carry the trigger flag, so a game tells a pressure
  /// plate or a goal line from the rest; queries skip triggers unless asked
  /// (QueryFilter2D::include_triggers).
  bool trigger = false;
  /// Never turns: infinite rotational inertia (characters, top-down discs).
  bool lock_rotation = false;
  /// Continuous collision (dynamic bodies): after each step a body that
  /// moved farther than the speculative distance is swept along the step's
  /// translation, at its end rotation, against every static and kinematic
  /// shape in its path, and moved back to the first touch with its velocity
  /// kept, so the next step's contact stops it (a bullet never crosses a
  /// thin wall). Costs nothing for bodies without it.
  bool continuous = false;
  uint64_t user_data = 0;  ///< game tag; part of state and the checksum
};

}  // namespace rwd::sim2d
