// SPDX-License-Identifier: MIT
#pragma once
// A kinematic character for the 3D lane: a capsule standing along an up
// axis, moved by shape casts against the world, sliding along what it
// meets (along the crease where two surfaces meet), stepping up ledges no
// higher than step_height, treating slopes steeper than the maximum as
// walls, and reporting whether it stands on walkable ground.
//
// The character is not a body: the world never moves it and it pushes
// nothing. move_character() is a pure function of the world's state, the
// character's state and the inputs, in float32 with + - * / and sqrt only,
// so the game keeps CharacterState3D in its own rollback state and gets
// the same bits when it replays a tick.
//
// A game that wants other bodies to meet the character gives it a
// kinematic capsule body of the same size, moves that body to
// state.position after each move (World3D::set_transform), and passes its
// id as `filter.ignore` so the character does not collide with itself.
#include <cstdint>

#include "rewind/sim/body.h"
#include "rewind/sim/math.h"
#include "rewind/sim/query.h"

namespace rwd::sim {

class World3D;

/// The character's shape and limits (m unless said). A value outside its
/// range is clamped into it; a non-finite value takes the default.
struct CharacterConfig3D {
  float radius = 0.3f;       ///< capsule radius, [2^-8, 10]
  float half_height = 0.5f;  ///< half the straight part (0: a sphere), [0, 10]
  float step_height = 0.3f;  ///< highest ledge climbed without jumping, [0, 10]
  /// Cosine of the steepest walkable slope, [0, 1]: 0.7071 walks up to 45
  /// degrees. A surface whose normal has a smaller component along `up` is
  /// a wall: it stops sideways moves and never lifts the character.
  float max_slope_cos = 0.7071f;
  /// Gap kept between the capsule and every surface, [2^-12, 1]; the ground
  /// probe reaches twice this far.
  float skin = 0.01f;
  int32_t max_slides = 4;  ///< casts per pass before giving up, [1, 8]
  /// The capsule's axis and the direction ground is walked on, normalized
  /// by the move; a zero or non-finite vector means +y.
  Vec3 up{0.0f, 1.0f, 0.0f};
};

/// What the game stores per character (and rolls back with its state).
struct CharacterState3D {
  Vec3 position;  ///< m, the capsule's centre
  /// m/s. The game's own (move_character never integrates it); the parts
  /// pressing into the surfaces met are removed, so gravity does not pile
  /// up while standing and a wall stops the push into it. A non-finite
  /// velocity becomes zero.
  Vec3 velocity;
  bool grounded = false;  ///< on walkable ground after the last move
  Vec3 ground_normal;     ///< unit, out of that ground; zero when airborne
  BodyId ground;          ///< the body stood on; null when airborne
  friend bool operator==(const CharacterState3D&, const CharacterState3D&) = default;
};

/// What one move did.
struct CharacterMove3D {
  Vec3 translation;          ///< m, where the capsule went
  bool hit_wall = false;     ///< a wall or too-steep slope blocked a sideways move
  bool hit_ceiling = false;  ///< something above stopped an upward move
  bool stepped_up = false;   ///< climbed a ledge
};

/// Moves the character by `desired` (m; the game's velocity x dt plus
/// gravity): first across `up` (sliding, stepping up when grounded and
/// blocked), then along it (landing stops on walkable ground, steep ground
/// slides it off, a ceiling stops a rise), then probes down to report the
/// ground, keeping a grounded character on slopes and steps going down (it
/// snaps down by up to step_height when it was grounded and is not moving
/// up). The probe also lifts the capsule out of ground that rose into it
/// (a platform moving up), by up to half the radius per move.
///
/// Bodies the filter passes are solid to it; sensors are not unless asked
/// for. A non-finite `desired` is treated as zero and a longer one than
/// 1000 m is shortened to that; a non-finite position moves nothing. A
/// body the capsule starts out touching does not hold back a move that
/// leaves it. It does not carry the character with a moving platform: the
/// game adds the platform's motion (state.ground's velocity x dt) to
/// `desired`. Allocates nothing once warm (the first move that starts
/// touching a body grows a per-thread buffer once).
CharacterMove3D move_character(const World3D& world, CharacterState3D& state, Vec3 desired,
                               const CharacterConfig3D& config, const QueryFilter& filter = {});

}  // namespace rwd::sim
