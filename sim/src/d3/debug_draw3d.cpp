// SPDX-License-Identifier: MIT
// Debug draw of a World3D (rewind/sim/debug_draw3d.h): reads the state,
// writes only the caller's buffers.
#include "rewind/sim/debug_draw3d.h"

#include <algorithm>

#include "d3/body_storage.h"
#include "d3/draw_shapes3d.h"
#include "d3/mass_frame.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

DrawColor body_color(const BodyInfo& info, uint32_t index, const DebugDrawOptions& o) {
  const DrawColors& c = o.colors;
  if (std::find(o.highlight_bodies.begin(), o.highlight_bodies.end(), index) !=
      o.highlight_bodies.end()) {
    return c.highlight;
  }
  if (info.enabled == 0) return c.disabled_body;
  if (info.sensor != 0) return c.sensor_body;
  if (info.kind == BodyKind::kStatic) return c.static_body;
  if (info.kind == BodyKind::kKinematic) return c.kinematic_body;
  return info.awake != 0 ? c.awake_body : c.asleep_body;
}

void line(DebugDrawBuffers& out, Vec3 a, Vec3 b, DrawColor color) {
  out.add_line(a.x, a.y, a.z, b.x, b.y, b.z, color);
}

/// Three short lines through p along the world axes.
void cross_at(DebugDrawBuffers& out, Vec3 p, float half, DrawColor color) {
  line(out, p - Vec3{half, 0.0f, 0.0f}, p + Vec3{half, 0.0f, 0.0f}, color);
  line(out, p - Vec3{0.0f, half, 0.0f}, p + Vec3{0.0f, half, 0.0f}, color);
  line(out, p - Vec3{0.0f, 0.0f, half}, p + Vec3{0.0f, 0.0f, half}, color);
}

void draw_bodies(const WorldState& s, const GeometryStore& store, const DebugDrawOptions& o,
                 DebugDrawBuffers& out) {
  for (uint32_t i = 0; i < s.infos.size(); ++i) {
    const BodyInfo& info = s.infos[i];
    if (info.alive == 0) continue;
    const BodySim& sim = s.sims[i];
    if (info.kind != BodyKind::kStatic || o.static_shapes) {
      d3::draw_shape_mass_frame(store, info.shape, sim.position, sim.rotation,
                                body_color(info, i, o), o, out);
    }
    if (o.bounds) {
      const d3::Aabb box = d3::shape_aabb(info.shape, sim.position, sim.rotation);
      d3::draw_box_edges(box.lower, box.upper, o.colors.bounds, out);
    }
    if (o.centers_of_mass) {  // the mass frame's axes in red, green and blue
      const Mat3 axes = mat3_from_quat(sim.rotation);
      line(out, sim.position, sim.position + axes.c0 * o.axis_length_m, 0xFF3030FFu);
      line(out, sim.position, sim.position + axes.c1 * o.axis_length_m, 0x30FF30FFu);
      line(out, sim.position, sim.position + axes.c2 * o.axis_length_m, 0x3070FFFFu);
    }
  }
}

void draw_contacts(const WorldState& s, const DebugDrawOptions& o, DebugDrawBuffers& out) {
  for (const ContactRecord& rec : s.contacts) {
    if (rec.touching == 0 || rec.sensor != 0 || rec.point_count == 0) continue;
    const BodySim& a = s.sims[rec.index_a];
    const Vec3 normal = rotate(a.rotation, rec.frame_normal);
    for (uint32_t k = 0; k < rec.point_count; ++k) {
      const CachedContactPoint& cp = rec.points[k];
      // The point is on A's surface; midway to B's is half the separation on.
      const Vec3 p = a.position + rotate(a.rotation, cp.local_a) + normal * (0.5f * cp.separation);
      const DrawColor color =
          cp.separation <= 0.0f ? o.colors.contact_touching : o.colors.contact_speculative;
      out.add_point(p.x, p.y, p.z, color, o.contact_point_px);
      if (o.contact_normals) line(out, p, p + normal * o.normal_length_m, o.colors.contact_normal);
    }
  }
}

Vec3 joint_anchor(const WorldState& s, uint32_t index, Vec3 local) {
  if (index == kJointWorld) return local;
  const BodySim& b = s.sims[index];
  return b.position + rotate(b.rotation, local);
}

void draw_joints(const WorldState& s, const DebugDrawOptions& o, DebugDrawBuffers& out) {
  const float half = 0.25f * o.axis_length_m;
  for (const JointRecord& j : s.joints) {
    if (j.alive == 0) continue;
    const DrawColor color = (j.flags & kJointBroken) != 0 ? o.colors.joint_broken : o.colors.joint;
    const Vec3 a = joint_anchor(s, j.index_a, j.local_anchor_a);
    const Vec3 b = joint_anchor(s, j.index_b, j.local_anchor_b);
    // A joint's line runs from each body's centre to its anchor and between
    // the anchors, so a stretched joint shows which bodies it holds.
    if (j.index_a != kJointWorld) line(out, s.sims[j.index_a].position, a, color);
    line(out, s.sims[j.index_b].position, b, color);
    line(out, a, b, color);
    cross_at(out, a, half, color);
    cross_at(out, b, half, color);
  }
}

}  // namespace

void debug_draw(const World3D& world, const DebugDrawOptions& options, DebugDrawBuffers& out) {
  const DebugDrawOptions o = sanitized(options);
  const WorldState& s = world.state();
  draw_bodies(s, world.geometry(), o, out);
  if (o.contacts) draw_contacts(s, o, out);
  if (o.joints) draw_joints(s, o, out);
}

WorldViewStats view_stats(const World3D& world) {
  const WorldState& s = world.state();
  WorldViewStats v;
  for (const BodyInfo& info : s.infos) {
    v.bodies += info.alive;
    v.awake_bodies += info.alive != 0 && info.awake != 0 ? 1u : 0u;
  }
  const ContactRecord* counted = nullptr;  // a compound pair has a record per part: once each
  for (const ContactRecord& rec : s.contacts) {
    if (rec.touching == 0) continue;
    if (counted == nullptr || counted->index_a != rec.index_a || counted->index_b != rec.index_b) {
      ++v.touching_pairs;
      counted = &rec;
    }
    v.contact_points += rec.sensor == 0 ? rec.point_count : 0u;
  }
  for (const JointRecord& j : s.joints) v.joints += j.alive;
  return v;
}

void draw_shape(const GeometryStore& store, const Shape& shape, Vec3 position, Quat rotation,
                DrawColor color, const DebugDrawOptions& options, DebugDrawBuffers& out) {
  if (!is_finite(position) || !is_finite(rotation) || length_squared(rotation) == 0.0f) return;
  if (shape.uses_geometry() && !store.contains(GeometryId{shape.geometry})) return;
  if (shape.uses_geometry()) {
    const std::optional<GeometryKind> kind = store.kind(GeometryId{shape.geometry});
    const bool matches =
        (shape.type == ShapeType::kHull && kind == GeometryKind::kHull) ||
        (shape.type == ShapeType::kMesh && kind == GeometryKind::kMesh) ||
        (shape.type == ShapeType::kHeightField && kind == GeometryKind::kHeightField) ||
        (shape.type == ShapeType::kCompound && kind == GeometryKind::kCompound);
    if (!matches) return;
  }
  const DebugDrawOptions o = sanitized(options);
  Vec3 mass_position;
  Quat mass_rotation;
  d3::authored_to_mass(d3::mass_frame(shape, store), position, normalize(rotation), mass_position,
                       mass_rotation);
  d3::draw_shape_mass_frame(store, shape, mass_position, mass_rotation, color, o, out);
}

}  // namespace rwd::sim
