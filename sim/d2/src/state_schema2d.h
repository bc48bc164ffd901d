// SPDX-License-Identifier: MIT
#pragma once
// The one description of the 2D state's persisted fields (DESIGN 6a): the
// writer, the reader, the checksum and the readable dump all walk these
// lists, so a field added here is saved, loaded, hashed and dumped alike.
//
// A visitor is called as v(name, field) with field one of uint8_t,
// uint16_t, uint32_t, uint64_t, W (int64_t, Q32.32), Fx or BodyKind2D, const
// for the writers and mutable for the reader. Names are string literals.
#include <cstdint>

#include "rewind/sim2d/world2d_state.h"

namespace rwd::sim2d::detail {

inline constexpr const char* kVertexNames[kMaxPolygonVertices][2] = {
    {"shape.vertex0.x", "shape.vertex0.y"}, {"shape.vertex1.x", "shape.vertex1.y"},
    {"shape.vertex2.x", "shape.vertex2.y"}, {"shape.vertex3.x", "shape.vertex3.y"},
    {"shape.vertex4.x", "shape.vertex4.y"}, {"shape.vertex5.x", "shape.vertex5.y"},
    {"shape.vertex6.x", "shape.vertex6.y"}, {"shape.vertex7.x", "shape.vertex7.y"}};
inline constexpr const char* kNormalNames[kMaxPolygonVertices][2] = {
    {"shape.normal0.x", "shape.normal0.y"}, {"shape.normal1.x", "shape.normal1.y"},
    {"shape.normal2.x", "shape.normal2.y"}, {"shape.normal3.x", "shape.normal3.y"},
    {"shape.normal4.x", "shape.normal4.y"}, {"shape.normal5.x", "shape.normal5.y"},
    {"shape.normal6.x", "shape.normal6.y"}, {"shape.normal7.x", "shape.normal7.y"}};

/// The configuration, in encode_config()'s order.
template <class Config, class Visitor>
void visit_config(Config& c, Visitor& v) {
  v("gravity.x", c.gravity.x);
  v("gravity.y", c.gravity.y);
  v("tick_hz", c.tick_hz);
  v("substeps", c.substeps);
  v("relax_iterations", c.relax_iterations);
  v("contact_hertz", c.contact_hertz);
  v("contact_damping_ratio", c.contact_damping_ratio);
  v("contact_push_max", c.contact_push_max);
  v("restitution_threshold", c.restitution_threshold);
  v("linear_slop", c.linear_slop);
  v("speculative_distance", c.speculative_distance);
  v("max_linear_speed", c.max_linear_speed);
  v("max_bodies", c.max_bodies);
  v("joint_damping_ratio", c.joint_damping_ratio);
  v("enable_sleep", c.enable_sleep);
  v("sleep_threshold", c.sleep_threshold);
  v("time_to_sleep", c.time_to_sleep);
  v("bounds_lower.x", c.bounds_lower.x);
  v("bounds_lower.y", c.bounds_lower.y);
  v("bounds_upper.x", c.bounds_upper.x);
  v("bounds_upper.y", c.bounds_upper.y);
}

/// Every slot starts with these; a free slot (no kBodyLive flag) has
/// nothing more: its other fields are zero.
template <class Body, class Visitor>
void visit_slot_head(Body& body, Visitor& v) {
  v("generation", body.generation);
  v("flags", body.flags);
}

/// The rest of a live body: the dynamic fields first (what desync reports
/// read first), then its fixed properties and its shape.
template <class Body, class Visitor>
void visit_body_rest(Body& body, Visitor& v) {
  v("kind", body.kind);
  v("center.x", body.center.x);
  v("center.y", body.center.y);
  v("rotation.c", body.rotation.c);
  v("rotation.s", body.rotation.s);
  v("velocity.x", body.velocity.x);
  v("velocity.y", body.velocity.y);
  v("angular_velocity", body.angular_velocity);
  v("force.x", body.force.x);
  v("force.y", body.force.y);
  v("torque", body.torque);
  v("sleep_time", body.sleep_time);
  v("z", body.z);
  v("user_data", body.user_data);
  v("layer", body.layer);
  v("mask", body.mask);
  v("local_center.x", body.local_center.x);
  v("local_center.y", body.local_center.y);
  v("inv_mass", body.inv_mass);
  v("inv_inertia", body.inv_inertia);
  v("linear_damping", body.linear_damping);
  v("angular_damping", body.angular_damping);
  v("gravity_scale", body.gravity_scale);
  v("friction", body.material.friction);
  v("restitution", body.material.restitution);
  v("rolling_resistance", body.material.rolling_resistance);
  v("shape.type", body.shape.type);
  v("shape.count", body.shape.count);
  v("shape.radius", body.shape.radius);
  for (int i = 0; i < kMaxPolygonVertices; ++i) {
    v(kVertexNames[i][0], body.shape.vertices[i].x);
    v(kVertexNames[i][1], body.shape.vertices[i].y);
  }
  for (int i = 0; i < kMaxPolygonVertices; ++i) {
    v(kNormalNames[i][0], body.shape.normals[i].x);
    v(kNormalNames[i][1], body.shape.normals[i].y);
  }
  v("shape.centroid.x", body.shape.centroid.x);
  v("shape.centroid.y", body.shape.centroid.y);
}

template <class Point, class Visitor>
void visit_contact_point(Point& p, Visitor& v) {
  v("anchor_a.x", p.anchor_a.x);
  v("anchor_a.y", p.anchor_a.y);
  v("anchor_b.x", p.anchor_b.x);
  v("anchor_b.y", p.anchor_b.y);
  v("separation", p.separation);
  v("normal_impulse", p.normal_impulse);
  v("tangent_impulse", p.tangent_impulse);
  v("id", p.id);
}

/// Only the `count` meaningful points are persisted.
template <class Contact, class Visitor>
void visit_contact(Contact& c, Visitor& v) {
  v("a", c.a);
  v("b", c.b);
  v("normal.x", c.normal.x);
  v("normal.y", c.normal.y);
  v("rolling_impulse", c.rolling_impulse);
  v("count", c.count);
  v("flags", c.flags);
  for (int i = 0; i < c.count && i < 2; ++i) visit_contact_point(c.points[i], v);
}

/// Every joint slot starts with these; a free slot has nothing more.
template <class Joint, class Visitor>
void visit_joint_head(Joint& j, Visitor& v) {
  v("generation", j.generation);
  v("flags", j.flags);
}

template <class Joint, class Visitor>
void visit_joint_rest(Joint& j, Visitor& v) {
  v("type", j.type);
  v("a", j.a);
  v("b", j.b);
  v("local_anchor_a.x", j.local_anchor_a.x);
  v("local_anchor_a.y", j.local_anchor_a.y);
  v("local_anchor_b.x", j.local_anchor_b.x);
  v("local_anchor_b.y", j.local_anchor_b.y);
  v("local_axis_a.x", j.local_axis_a.x);
  v("local_axis_a.y", j.local_axis_a.y);
  v("reference_angle", j.reference_angle);
  v("length", j.length);
  v("min_length", j.min_length);
  v("max_length", j.max_length);
  v("lower", j.lower);
  v("upper", j.upper);
  v("motor_speed", j.motor_speed);
  v("max_motor", j.max_motor);
  v("hertz", j.hertz);
  v("damping_ratio", j.damping_ratio);
  v("linear_hertz", j.linear_hertz);
  v("angular_hertz", j.angular_hertz);
  v("max_force", j.max_force);
  v("break_impulse", j.break_impulse);
  v("target.x", j.target.x);
  v("target.y", j.target.y);
  v("linear_impulse.x", j.linear_impulse.x);
  v("linear_impulse.y", j.linear_impulse.y);
  v("angular_impulse", j.angular_impulse);
  v("axial_impulse", j.axial_impulse);
  v("spring_impulse", j.spring_impulse);
  v("motor_impulse", j.motor_impulse);
  v("lower_impulse", j.lower_impulse);
  v("upper_impulse", j.upper_impulse);
}

template <class Exit, class Visitor>
void visit_pending_exit(Exit& e, Visitor& v) {
  v("a", e.a);
  v("generation_a", e.generation_a);
  v("b", e.b);
  v("generation_b", e.generation_b);
  v("sensor", e.sensor);
}

}  // namespace rwd::sim2d::detail
