// SPDX-License-Identifier: MIT
#pragma once
// Bodies of the 2D lane: handles, kinds and the definition a body is made
// from. Public values are Q16.16 (Fx) in metres, seconds, kilograms and
// radians, masses and inertias Q32.32 (FxWide); the world keeps them all in
// Q32.32 inside.
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/fx_wide.h"
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

// The range of a dynamic body's mass and rotational inertia. The solver
// works with their inverses in Q32.32, so the heaviest bodies keep fewer
// significant bits there: a body moves as if its mass were off by a
// fraction below m / 2^32 kg (0.025% at the limit) and turns as if its
// inertia were off by a fraction below I / 2^32 kg m^2 (6% at the limit; a
// 40 t plate 200 m square is 0.6% off), the same in every row it is solved
// in, so it still behaves as one consistent rigid body. Impulses grow as
// mass x speed and their turning effect as mass x size x speed: the step's
// integer range holds them for a 40 t body (even a 200 m plate) up to the
// default speed cap of 400 m/s, but only up to about 100 m/s of impact
// speed for a body at both upper limits at once. The lower limits refuse
// only bodies whose inverse would not fit (a disc of density 1 less than
// 1 cm across: lock its rotation or make it denser).

/// The lightest dynamic body, kg: 2^-30 (about 1 microgram).
inline constexpr fixed::FxWide kMinBodyMass2D = fixed::FxWide::from_raw(4);
/// The heaviest dynamic body, kg: 2^20 = 1,048,576 (about 1,000 t).
inline constexpr fixed::FxWide kMaxBodyMass2D = fixed::FxWide::from_raw(int64_t{1} << 52);
/// The smallest rotational inertia about the centre of mass, kg m^2: 2^-30.
inline constexpr fixed::FxWide kMinBodyInertia2D = fixed::FxWide::from_raw(4);
/// The largest, kg m^2: 2^28 = 268,435,456 (a 200 m x 200 m plate of
/// 40 t has 2.67e8).
inline constexpr fixed::FxWide kMaxBodyInertia2D = fixed::FxWide::from_raw(int64_t{1} << 60);

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
  /// kg/m^2, (0, 30000]; dynamic bodies only. The body's mass (shape area
  /// x density) must lie in [kMinBodyMass2D, kMaxBodyMass2D] and its
  /// rotational inertia in [kMinBodyInertia2D, kMaxBodyInertia2D] (not
  /// checked with lock_rotation); create_body() refuses it otherwise.
  Fx density = 1_fx;
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
  /// false: a dynamic body starts asleep, exactly as one that fell asleep
  /// (World2D::is_awake() is false): it stays where it is put, even in
  /// mid-air, until something wakes it: a touch by a moving body, a joint
  /// created to it or to a moving body, a force, impulse, velocity or
  /// transform set on it, or wake_body() (in a world with enable_sleep off
  /// too). Its velocities must then be zero (a sleeping body has none).
  /// Ignored for static and kinematic bodies (they are never awake). Part
  /// of state like every sleeping body.
  bool awake = true;
  uint64_t user_data = 0;  ///< game tag; part of state and the checksum
};

}  // namespace rwd::sim2d
