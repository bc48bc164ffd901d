// SPDX-License-Identifier: MIT
// The portable bytes of a 2D world (resync snapshots): "RW2D", a format
// version, the config, the step count, every slot and every contact, each
// field little-endian as the schema lists it. Reading checks everything a
// later step relies on, so a corrupt snapshot is refused, never stepped.
#include <string>
#include <utility>

#include "byte_codec2d.h"
#include "rewind/sim2d/world2d.h"
#include "state_schema2d.h"

namespace rwd::sim2d {

using namespace detail;

namespace {

constexpr uint32_t kMagic = 0x44325752;  // "RW2D" little-endian
constexpr uint32_t kFormatVersion = 1;

Status corrupt(const std::string& what) {
  return Status::Error(ErrorCode::kCorrupt, "2D world snapshot: " + what);
}

constexpr uint8_t kKnownFlags = kBodyEnabled | kBodySensor | kBodyLockRotation | kBodyLive |
                                kBodyAwake | kBodyContinuous | kBodyTrigger;

Status check_body(const BodyRecord2D& body, const World2DConfig& config, uint32_t index) {
  const std::string at = "body " + std::to_string(index) + ": ";
  if (body.generation == 0) return corrupt(at + "generation 0");
  if ((body.flags & ~kKnownFlags) != 0) return corrupt(at + "unknown flags");
  if (static_cast<uint8_t>(body.kind) > static_cast<uint8_t>(BodyKind2D::kDynamic)) {
    return corrupt(at + "unknown kind");
  }
  if (Status s = validate_shape(body.shape); !s.ok()) return corrupt(at + s.message());
  const V2 lower = v_from(config.bounds_lower);
  const V2 upper = v_from(config.bounds_upper);
  if (body.center.x < lower.x || body.center.x > upper.x || body.center.y < lower.y ||
      body.center.y > upper.y) {
    return corrupt(at + "centre outside the world bounds");
  }
  // A rotation must be unit to well within its last bits' drift.
  const W m2 = wmul_add(body.rotation.c, body.rotation.c, body.rotation.s, body.rotation.s);
  if (wabs(m2 - kWOne) > (kWOne >> 16)) return corrupt(at + "rotation is not unit length");
  const W cap = w_from(config.max_linear_speed);
  if (wabs(body.velocity.x) > cap || wabs(body.velocity.y) > cap) {
    return corrupt(at + "velocity beyond max_linear_speed");
  }
  if (body.inv_mass < 0 || body.inv_inertia < 0) return corrupt(at + "negative inverse mass");
  if (body.sleep_time < 0) return corrupt(at + "negative sleep time");
  if (body.kind != BodyKind2D::kDynamic && (body.inv_mass != 0 || body.inv_inertia != 0)) {
    return corrupt(at + "a static or kinematic body with finite mass");
  }
  // A dynamic body's inverses are those of a mass and inertia create_body()
  // accepts (body2d.h), so a snapshot cannot bring in a body the step's
  // integer range was never sized for.
  if (body.kind == BodyKind2D::kDynamic) {
    if (body.inv_mass < winv(kMaxBodyMass2D.raw()) || body.inv_mass > winv(kMinBodyMass2D.raw())) {
      return corrupt(at + "mass outside the 2D lane's range");
    }
    const bool locked = (body.flags & kBodyLockRotation) != 0;
    if (locked ? body.inv_inertia != 0
               : (body.inv_inertia < winv(kMaxBodyInertia2D.raw()) ||
                  body.inv_inertia > winv(kMinBodyInertia2D.raw()))) {
      return corrupt(at + "rotational inertia outside the 2D lane's range");
    }
  }
  return Status::Ok();
}

constexpr uint8_t kKnownJointFlags =
    kJointLive | kJointBroken | kJointCollideConnected | kJointLimit | kJointMotor | kJointSpring;

Status check_joint(const JointRecord2D& j, const World2DState& state, uint32_t index) {
  const std::string at = "joint " + std::to_string(index) + ": ";
  if (j.generation == 0) return corrupt(at + "generation 0");
  if (!(j.flags & kJointLive) || (j.flags & ~kKnownJointFlags) != 0)
    return corrupt(at + "bad flags");
  if (static_cast<uint8_t>(j.type) > static_cast<uint8_t>(JointType2D::kGrab)) {
    return corrupt(at + "unknown type");
  }
  if (j.a == j.b || j.a >= state.bodies.size() || j.b >= state.bodies.size() ||
      !(state.bodies[j.a].flags & kBodyLive) || !(state.bodies[j.b].flags & kBodyLive)) {
    return corrupt(at + "bodies are not two live bodies");
  }
  if (j.hertz < 0 || j.damping_ratio < 0 || j.linear_hertz < 0 || j.angular_hertz < 0 ||
      j.max_motor < 0 || j.max_force < 0 || j.break_impulse < 0 || j.min_length < 0 ||
      j.max_length < j.min_length || j.upper < j.lower) {
    return corrupt(at + "a parameter out of range");
  }
  if ((j.flags & kJointSpring) && (j.hertz <= 0 || j.hertz > w_int(1000))) {
    return corrupt(at + "spring hertz out of range");
  }
  const W axis2 = vlength_sq(j.local_axis_a);
  if ((j.type == JointType2D::kPrismatic || j.type == JointType2D::kWheel) &&
      wabs(axis2 - kWOne) > (kWOne >> 12)) {
    return corrupt(at + "axis is not unit length");
  }
  return Status::Ok();
}

}  // namespace

void World2D::serialize(std::vector<uint8_t>& out) const {
  out.clear();
  ByteWriter2D writer(out);
  writer.put(kMagic, 4);
  writer.put(kFormatVersion, 4);
  std::vector<uint8_t> config;
  encode_config(state_.config, config);
  writer.put(config.size(), 4);
  out.insert(out.end(), config.begin(), config.end());
  writer.put(state_.step_count, 8);
  writer.put(state_.bodies.size(), 4);
  for (const BodyRecord2D& body : state_.bodies) {
    visit_slot_head(body, writer);
    if (body.flags & kBodyLive) visit_body_rest(body, writer);
  }
  writer.put(state_.contacts.size(), 4);
  for (const ContactRecord2D& contact : state_.contacts) visit_contact(contact, writer);
  writer.put(state_.pending_exits.size(), 4);
  for (const PendingExit2D& exit : state_.pending_exits) visit_pending_exit(exit, writer);
  writer.put(state_.joints.size(), 4);
  for (const JointRecord2D& joint : state_.joints) {
    visit_joint_head(joint, writer);
    if (joint.flags & kJointLive) visit_joint_rest(joint, writer);
  }
}

Status World2D::deserialize(std::span<const uint8_t> bytes) {
  ByteReader2D reader(bytes);
  if (reader.get(4) != kMagic) return corrupt("not a 2D world snapshot");
  if (reader.get(4) != kFormatVersion) return corrupt("unknown format version");
  const auto config_bytes = reader.take(static_cast<size_t>(reader.get(4)));
  if (!reader.ok()) return corrupt("truncated config");
  Result<World2DConfig> config = decode_config(config_bytes);
  if (!config.ok()) return corrupt(config.status().message());

  World2DState state;
  state.config = *config;
  state.step_count = reader.get(8);
  const uint64_t slots = reader.get(4);
  if (!reader.ok() || slots > state.config.max_bodies)
    return corrupt("slot count beyond max_bodies");
  // Each slot takes at least 5 bytes: refuse counts the bytes cannot hold
  // before reserving memory for them.
  if (slots * 5 > bytes.size()) return corrupt("truncated bodies");
  state.bodies.resize(static_cast<size_t>(slots));
  for (uint32_t i = 0; i < slots; ++i) {
    BodyRecord2D& body = state.bodies[i];
    visit_slot_head(body, reader);
    if (!reader.ok()) return corrupt("truncated bodies");
    if (body.flags == 0) continue;
    if (!(body.flags & kBodyLive)) return corrupt("body " + std::to_string(i) + ": bad slot flags");
    visit_body_rest(body, reader);
    if (!reader.ok()) return corrupt("truncated bodies");
    if (Status s = check_body(body, state.config, i); !s.ok()) return s;
    ++state.live_bodies;
  }
  const uint64_t contacts = reader.get(4);
  // A contact takes at least 49 bytes.
  if (!reader.ok() || contacts * 49 > bytes.size()) return corrupt("truncated contacts");
  state.contacts.resize(static_cast<size_t>(contacts));
  uint64_t previous_key = 0;
  for (uint32_t i = 0; i < contacts; ++i) {
    ContactRecord2D& contact = state.contacts[i];
    // The point count bounds the points read; check it before trusting it.
    visit_contact(contact, reader);
    if (!reader.ok()) return corrupt("truncated contacts");
    const std::string at = "contact " + std::to_string(i) + ": ";
    if (contact.count < 1 || contact.count > 2) return corrupt(at + "point count not 1 or 2");
    if ((contact.flags & ~(kContactSensor | kContactTouching | kContactTrigger)) != 0) {
      return corrupt(at + "unknown flags");
    }
    if (contact.a >= contact.b || contact.b >= slots ||
        !(state.bodies[contact.a].flags & kBodyLive) ||
        !(state.bodies[contact.b].flags & kBodyLive)) {
      return corrupt(at + "bodies not a live pair in order");
    }
    const uint64_t key = (uint64_t{contact.a} << 32) | contact.b;
    if (i > 0 && key <= previous_key) return corrupt(at + "contacts out of order");
    previous_key = key;
    const W n2 = vlength_sq(contact.normal);
    if (wabs(n2 - kWOne) > (kWOne >> 12)) return corrupt(at + "normal is not unit length");
  }
  const uint64_t exits = reader.get(4);
  // An exit takes 17 bytes.
  if (!reader.ok() || exits * 17 > bytes.size()) return corrupt("truncated pending exits");
  state.pending_exits.resize(static_cast<size_t>(exits));
  for (PendingExit2D& exit : state.pending_exits) {
    visit_pending_exit(exit, reader);
    if (exit.a >= exit.b || exit.sensor > 3) return corrupt("bad pending exit");
  }
  if (!reader.ok()) return corrupt("truncated pending exits");
  const uint64_t joint_slots = reader.get(4);
  // A joint slot takes at least 5 bytes.
  if (!reader.ok() || joint_slots > state.config.max_bodies || joint_slots * 5 > bytes.size()) {
    return corrupt("bad joint count");
  }
  state.joints.resize(static_cast<size_t>(joint_slots));
  for (uint32_t i = 0; i < joint_slots; ++i) {
    JointRecord2D& joint = state.joints[i];
    visit_joint_head(joint, reader);
    if (!reader.ok()) return corrupt("truncated joints");
    if (joint.flags == 0) continue;
    visit_joint_rest(joint, reader);
    if (!reader.ok()) return corrupt("truncated joints");
    if (Status s = check_joint(joint, state, i); !s.ok()) return s;
    ++state.live_joints;
  }
  if (!reader.at_end()) return corrupt("trailing bytes");
  state_ = std::move(state);
  ++body_edits_;
  stats_ = {};
  return Status::Ok();
}

}  // namespace rwd::sim2d
