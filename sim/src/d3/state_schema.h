// SPDX-License-Identifier: MIT
#pragma once
// The one description of every persisted field of WorldState: its name, its
// encoding and its place in the canonical order. The snapshot writer, the
// checksum (state_io.cpp), the snapshot reader (state_io.cpp) and the
// readable dump (state_dump.cpp) all walk these functions, so a new field is
// added here once and every view of the state has it, in the same place.
//
// An Io visits each field through one of these members, by name:
//   u8, u32, u64, f32, vec3, quat   plain values
//   i32                             a signed 32-bit count, stored as u32
//   flag                            0 or 1 in a byte (a reader refuses more)
//   boolean                         a bool as a flag
//   enumeration(name, v, last)      an enum stored in a byte, 0 .. last
//   count(name, v, max)             a byte count of what follows, <= max
//   event_mask(name, v)             a body's EventMask, in one byte coded
//                                   by encode_event_mask (a reader refuses
//                                   other bytes)
// The visited structs may be const (writers, the dump) or not (the reader,
// which fills them as it goes: a field decided by an earlier one, such as
// the shape's sizes by its type, is read after it).
#include <cstdint>

#include "d3/shape_ops.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

// A body's event mask takes the byte the boolean contact_events flag had:
// 0 for no event, 1 for every event, and 0x80 | the bits for any other
// mask. Worlds whose bodies report all or nothing (every world before masks
// existed) so keep their snapshot bytes and their checksum.
inline constexpr uint8_t kEventMaskSelection = 0x80;

/// The stored byte of an event mask (bits within kEventAll).
inline uint8_t encode_event_mask(EventMask mask) {
  if (mask == kEventAll) return 1;
  if (mask == kEventNone) return 0;
  return static_cast<uint8_t>(kEventMaskSelection | mask);
}
/// The mask of a stored byte; false for a byte encode_event_mask never
/// writes.
inline bool decode_event_mask(uint8_t byte, EventMask& mask) {
  if (byte <= 1) {
    mask = byte == 1 ? kEventAll : kEventNone;
    return true;
  }
  const auto bits = static_cast<EventMask>(byte & ~kEventMaskSelection);
  mask = bits;
  return (byte & kEventMaskSelection) != 0 && (bits & ~kEventAll) == 0 && bits != kEventAll &&
         bits != kEventNone;
}

template <class Io, class Config>
[[gnu::always_inline]] inline void visit_config(Io& io, Config& c) {
  io.vec3("gravity", c.gravity);
  io.f32("tick_seconds", c.tick_seconds);
  io.i32("substeps", c.substeps);
  io.i32("relax_iterations", c.relax_iterations);
  io.f32("contact_hertz", c.contact_hertz);
  io.f32("contact_damping_ratio", c.contact_damping_ratio);
  io.f32("contact_push_max_mps", c.contact_push_max_mps);
  io.f32("restitution_threshold_mps", c.restitution_threshold_mps);
  io.f32("linear_slop_m", c.linear_slop_m);
  io.f32("speculative_distance_m", c.speculative_distance_m);
  io.boolean("enable_sleep", c.enable_sleep);
  io.f32("sleep_threshold_mps", c.sleep_threshold_mps);
  io.f32("time_to_sleep_s", c.time_to_sleep_s);
  io.u32("max_bodies", c.max_bodies);
  io.vec3("bounds_lower", c.bounds_lower);
  io.vec3("bounds_upper", c.bounds_upper);
}

/// The fields of a shape, as "shape.*".
template <class Io, class S>
[[gnu::always_inline]] inline void visit_shape(Io& io, S& shape) {
  io.enumeration("shape.type", shape.type, static_cast<ShapeType>(kShapeTypeCount - 1));
  if (shape.uses_geometry()) {
    // The shape's sizes are its geometry's; the id names it.
    io.u32("shape.geometry", shape.geometry);
  } else {
    io.f32("shape.radius", shape.radius);
    io.vec3("shape.half_extents", shape.half_extents);
    io.f32("shape.half_height", shape.half_height);
  }
}

/// The fields of a live body slot (its generation and alive flag, which
/// every slot has, are the caller's).
template <class Io, class Info, class Sim>
[[gnu::always_inline]] inline void visit_body(Io& io, Info& b, Sim& m) {
  io.enumeration("kind", b.kind, BodyKind::kDynamic);
  io.flag("sensor", b.sensor);
  io.flag("awake", b.awake);
  io.flag("enabled", b.enabled);
  visit_shape(io, b.shape);
  io.f32("material.friction", b.material.friction);
  io.f32("material.restitution", b.material.restitution);
  io.f32("material.rolling_resistance", b.material.rolling_resistance);
  io.u32("layer", b.layer);
  io.u32("mask", b.mask);
  io.u64("user_data", b.user_data);
  io.f32("density", b.density);
  io.f32("linear_damping", b.linear_damping);
  io.f32("angular_damping", b.angular_damping);
  io.f32("gravity_scale", b.gravity_scale);
  io.vec3("position", m.position);
  io.quat("rotation", m.rotation);
  io.vec3("linear_velocity", m.linear_velocity);
  io.vec3("angular_velocity", m.angular_velocity);
  io.vec3("force", m.force);
  io.vec3("torque", m.torque);
  io.u8("lock_rotation", b.lock_rotation);
  io.flag("continuous", b.continuous);
  io.event_mask("event_mask", b.event_mask);
  io.f32("sleep_time", m.sleep_time);
  io.vec3("sleep_position", m.sleep_position);
  io.quat("sleep_rotation", m.sleep_rotation);
}

/// The fields of one contact cache record.
template <class Io, class Record>
[[gnu::always_inline]] inline void visit_contact(Io& io, Record& r) {
  io.u32("index_a", r.index_a);
  io.u32("generation_a", r.generation_a);
  io.u32("index_b", r.index_b);
  io.u32("generation_b", r.generation_b);
  io.flag("touching", r.touching);
  io.flag("sensor", r.sensor);
  io.count("point_count", r.point_count, static_cast<uint8_t>(kMaxManifoldPoints));
  io.count("part", r.part, static_cast<uint8_t>(kMaxContactParts - 1));
  for (uint32_t p = 0; p < r.point_count; ++p) {
    auto& point = r.points[p];
    io.u32("point.feature_id", point.feature_id);
    io.f32("point.normal_impulse", point.normal_impulse);
    io.f32("point.tangent_impulse1", point.tangent_impulse1);
    io.f32("point.tangent_impulse2", point.tangent_impulse2);
    io.vec3("point.local_a", point.local_a);
    io.f32("point.separation", point.separation);
  }
  // A record without points has no manifold, so no frame.
  if (r.point_count == 0) return;
  io.vec3("frame_position", r.frame_position);
  io.quat("frame_rotation", r.frame_rotation);
  io.vec3("frame_normal", r.frame_normal);
}

/// The fields of a live joint slot (its generation and alive flag, which
/// every slot has, are the caller's).
template <class Io, class Joint>
[[gnu::always_inline]] inline void visit_joint(Io& io, Joint& j) {
  io.enumeration("type", j.type, static_cast<JointType>(kJointTypeCount - 1));
  io.u8("flags", j.flags);
  io.u32("index_a", j.index_a);
  io.u32("generation_a", j.generation_a);
  io.u32("index_b", j.index_b);
  io.u32("generation_b", j.generation_b);
  io.vec3("local_anchor_a", j.local_anchor_a);
  io.vec3("local_anchor_b", j.local_anchor_b);
  io.quat("frame_a", j.frame_a);
  io.quat("frame_b", j.frame_b);
  io.f32("lower", j.lower);
  io.f32("upper", j.upper);
  io.f32("cone_angle", j.cone_angle);
  io.f32("twist_lower", j.twist_lower);
  io.f32("twist_upper", j.twist_upper);
  io.f32("min_length", j.min_length);
  io.f32("max_length", j.max_length);
  io.f32("length", j.length);
  io.f32("motor_speed", j.motor_speed);
  io.vec3("motor_velocity", j.motor_velocity);
  io.f32("max_motor", j.max_motor);
  io.f32("hertz", j.hertz);
  io.f32("damping_ratio", j.damping_ratio);
  io.f32("spring_target", j.spring_target);
  io.quat("spring_rotation", j.spring_rotation);
  io.f32("linear_hertz", j.linear_hertz);
  io.f32("angular_hertz", j.angular_hertz);
  io.vec3("target", j.target);
  io.f32("max_force", j.max_force);
  io.f32("break_impulse", j.break_impulse);
  io.vec3("linear_impulse", j.linear_impulse);
  io.vec3("angular_impulse", j.angular_impulse);
  io.vec3("motor_impulse", j.motor_impulse);
  io.vec3("spring_impulse", j.spring_impulse);
  io.f32("axial_impulse", j.axial_impulse);
  io.f32("lower_impulse", j.lower_impulse);
  io.f32("upper_impulse", j.upper_impulse);
  io.f32("cone_impulse", j.cone_impulse);
}

/// The fields of one scheduled query (ScheduledQueryRecord): a ray's or
/// an overlap's, by its kind.
template <class Io, class Query>
[[gnu::always_inline]] inline void visit_query(Io& io, Query& q) {
  io.u64("ticket", q.ticket);
  io.u64("user_tag", q.user_tag);
  io.enumeration("kind", q.kind, ScheduledQueryKind::kOverlap);
  io.enumeration("phase", q.phase, QueryPhase::kPostPhysics);
  io.flag("repeat", q.repeat);
  io.u32("filter.layer_mask", q.filter.layer_mask);
  io.boolean("filter.include_sensors", q.filter.include_sensors);
  io.boolean("filter.include_static", q.filter.include_static);
  io.boolean("filter.include_kinematic", q.filter.include_kinematic);
  io.boolean("filter.include_dynamic", q.filter.include_dynamic);
  io.u32("filter.ignore.index", q.filter.ignore.index);
  io.u32("filter.ignore.generation", q.filter.ignore.generation);
  if (q.kind != ScheduledQueryKind::kOverlap) {
    io.vec3("ray.origin", q.ray.origin);
    io.vec3("ray.direction", q.ray.direction);
    io.f32("ray.max_distance", q.ray.max_distance);
    return;
  }
  visit_shape(io, q.shape);
  io.vec3("position", q.position);
  io.quat("rotation", q.rotation);
}

}  // namespace rwd::sim::d3
