// SPDX-License-Identifier: MIT
#pragma once
// A kinematic character for the 2D lane: an upright capsule moved by shape
// casts against the world, sliding along what it meets, stepping up
// ledges no higher than step_height, treating slopes steeper than the
// maximum as walls, and reporting whether it stands on walkable ground.
//
// The character is not a body: the world never moves it and it pushes
// nothing. move_character() is a pure function of the world's state, the
// character's state and the inputs, in integers only, so the game keeps
// CharacterState2D in its own rollback state and gets the same bits when
// it replays a tick.
#include <cstdint>

#include "rewind/fixed/fx.h"
#include "rewind/fixed/fx_literal.h"
#include "rewind/fixed/vec2.h"
#include "rewind/sim2d/body2d.h"
#include "rewind/sim2d/query2d.h"

namespace rwd::sim2d {

class World2D;

using namespace rwd::fixed::literals;

/// The character's shape and limits (m unless said). Values outside their
/// range are clamped into it.
struct CharacterConfig2D {
  Fx radius = 0.3_fx;       ///< capsule radius, [2^-8, 10]
  Fx half_height = 0.5_fx;  ///< half the straight part (0: a circle), [0, 10]
  Fx step_height = 0.3_fx;  ///< highest ledge climbed without jumping, [0, 10]
  /// Cosine of the steepest walkable slope, [0, 1]: 0.7071 walks up to 45
  /// degrees. A surface whose normal has a smaller upward component is a
  /// wall: it stops sideways moves and never lifts the character.
  Fx max_slope_cos = 0.7071_fx;
  /// Gap kept between the capsule and every surface, [2^-12, 1]; the ground
  /// probe reaches twice this far.
  Fx skin = 0.01_fx;
  int32_t max_slides = 4;  ///< casts per pass before giving up, [1, 8]
};

/// What the game stores per character (and rolls back with its state).
struct CharacterState2D {
  Vec2 position;  ///< m, the capsule's centre
  /// m/s. The game's own (move_character never integrates it); the parts
  /// pressing into the surfaces met are removed, so gravity does not pile
  /// up while standing and a wall stops the push into it.
  Vec2 velocity;
  bool grounded = false;  ///< on walkable ground after the last move
  Vec2 ground_normal;     ///< unit, out of that ground; zero when airborne
  BodyId2D ground;        ///< the body stood on; null when airborne
  friend bool operator==(const CharacterState2D&, const CharacterState2D&) = default;
};

/// What one move did.
struct CharacterMove2D {
  Vec2 translation;          ///< m, where the capsule went
  bool hit_wall = false;     ///< a wall or too-steep slope blocked a sideways move
  bool hit_ceiling = false;  ///< something above stopped an upward move
  bool stepped_up = false;   ///< climbed a ledge
};

/// Moves the character by `desired` (m; the game's velocity x dt plus
/// gravity): first sideways (sliding, stepping up when grounded and
/// blocked), then vertically (landing stops on walkable ground, steep
/// ground slides it off), then probes down to report the ground, keeping
/// a grounded character on slopes and steps going down (it snaps down by
/// up to step_height when it was grounded and is not moving up). Bodies
/// the filter passes are solid to it; sensors are not unless asked for.
CharacterMove2D move_character(const World2D& world, CharacterState2D& state, Vec2 desired,
                               const CharacterConfig2D& config, const QueryFilter2D& filter = {});

}  // namespace rwd::sim2d
