// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include "rewind/sim/event_mask.h"
#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"

namespace rwd::sim {

/// Handle to a body. `index` is the body's slot, `generation` tells a live
/// body from a destroyed one that used the same slot. Generation 0 is the
/// null handle. Slots are allocated deterministically (lowest free slot
/// first), so the same sequence of create/destroy calls yields the same ids
/// on every machine, and every result-affecting order derives from `index`.
struct BodyId {
  uint32_t index = 0;
  uint32_t generation = 0;
  bool is_null() const { return generation == 0; }
  friend bool operator==(BodyId, BodyId) = default;
};

enum class BodyKind : uint8_t {
  kStatic = 0,     ///< never moves; infinite mass
  kKinematic = 1,  ///< moves by the velocity you set; infinite mass, unaffected by contacts
  kDynamic = 2,    ///< moved by gravity, contacts and impulses
};

/// Surface response, combined per contact: friction by geometric mean,
/// restitution and rolling resistance by maximum.
struct Material {
  float friction = 0.6f;     ///< Coulomb coefficient, [0, 10]
  float restitution = 0.0f;  ///< bounce, [0, 1]
  /// Coefficient of rolling resistance, [0, 1]: a rolling contact is
  /// resisted by a torque up to this times the normal force times the
  /// lever from the body's centre of mass to the contact (a ball of radius
  /// r on flat ground slows by c g / (1 + I / (m r^2))). It opposes only
  /// turning about axes in the contact plane, never spinning about the
  /// normal. 0 (the default) costs nothing.
  float rolling_resistance = 0.0f;

  /// A material from the 0-10 authoring scale (each value / 10: friction
  /// 2 against 8 gives sqrt(0.2 * 0.8) = 0.4), as level tools author them.
  static Material from_authoring(float friction_0_10, float restitution_0_10,
                                 float rolling_0_10 = 0.0f) {
    return {friction_0_10 * 0.1f, restitution_0_10 * 0.1f, rolling_0_10 * 0.1f};
  }
};

/// World axes a dynamic body never turns about (BodyDef::lock_rotation):
/// a character capsule locks x and z to stay upright, kLockRotationAll
/// keeps a body from turning at all.
inline constexpr uint8_t kLockRotationX = 1;
inline constexpr uint8_t kLockRotationY = 2;
inline constexpr uint8_t kLockRotationZ = 4;
inline constexpr uint8_t kLockRotationAll = 7;

/// Everything needed to create a body. Values are validated (finite, in
/// range) and quantized to the canonical grid on creation.
struct BodyDef {
  BodyKind kind = BodyKind::kDynamic;
  Shape shape = Shape::make_box({0.5f, 0.5f, 0.5f});
  /// metres: the shape's centre; for a hull, the origin of the frame its
  /// points were given in (the body turns about its centre of mass)
  Vec3 position;
  Quat rotation;                  ///< normalized on creation
  Vec3 linear_velocity;           ///< m/s, of the centre of mass
  Vec3 angular_velocity;          ///< rad/s, world frame
  float density = 1000.0f;        ///< kg/m^3, > 0; dynamic bodies only
  float linear_damping = 0.0f;    ///< 1/s, >= 0
  float angular_damping = 0.05f;  ///< 1/s, >= 0
  float gravity_scale = 1.0f;     ///< multiplies world gravity
  Material material;
  uint32_t layer = 1;           ///< collision layer bits this body is on
  uint32_t mask = 0xFFFFFFFFu;  ///< layers this body collides with (both sides must agree)
  bool sensor = false;          ///< reports overlap events, never pushes
  uint64_t user_data = 0;       ///< game tag; part of state and the checksum
  /// kLockRotation* bits: world axes the body never turns about (its
  /// angular velocity about them stays zero, whatever pushes it), [0, 7].
  uint8_t lock_rotation = 0;
  /// Continuous collision: after each step the body (a compound by each
  /// of its children) is swept along the tick's translation, at its end
  /// rotation, against every shape in its path and, if it would have
  /// crossed one, moved back to the first touch (a bullet through a thin
  /// wall). Dynamic bodies only; costs nothing for bodies that leave it off.
  bool continuous = false;
  /// Which of this body's contact and sensor events World3D::events()
  /// reports (kEvent* bits, event_mask.h; a pair's event is reported when
  /// either body's mask asks for it). Every event by default.
  EventMask event_mask = kEventAll;
  /// Report this body's contacts at all: false reports none, whatever
  /// event_mask says (the body's mask becomes kEventNone). Off for bodies
  /// whose contacts no game rule reads (debris), so a big pile does not
  /// fill the event list.
  bool contact_events = true;
};

}  // namespace rwd::sim
