// SPDX-License-Identifier: MIT
// Debug draw of a World2D (rewind/sim2d/debug_draw2d.h). Runs outside the
// step and writes only the caller's float buffers: with world2d_hash.cpp,
// the lane's only file allowed floating point (tests/unit/sim2d).
#include "rewind/sim2d/debug_draw2d.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "body_math2d.h"
#include "rewind/core/det_math.h"
#include "rewind/sim2d/world2d.h"
#include "shape_bounds2d.h"
#include "wmath.h"

namespace rwd::sim2d {
namespace {

using rwd::DebugDrawBuffers;
using rwd::DebugDrawOptions;
using rwd::DrawColor;

struct F2 {
  float x = 0.0f;
  float y = 0.0f;
};
F2 operator+(F2 a, F2 b) {
  return {a.x + b.x, a.y + b.y};
}
F2 operator-(F2 a, F2 b) {
  return {a.x - b.x, a.y - b.y};
}
F2 operator*(F2 a, float s) {
  return {a.x * s, a.y * s};
}

float to_float(detail::W w) {
  return static_cast<float>(static_cast<double>(w) * 0x1p-32);
}
float to_float(Fx f) {
  return static_cast<float>(f.raw()) * 0x1p-16f;
}
F2 to_f2(detail::V2 v) {
  return {to_float(v.x), to_float(v.y)};
}
F2 to_f2(Vec2 v) {
  return {to_float(v.x), to_float(v.y)};
}

/// A body frame in float: origin and rotation.
struct Frame {
  F2 origin;
  float c = 1.0f;
  float s = 0.0f;
  F2 world(F2 local) const {
    return {origin.x + c * local.x - s * local.y, origin.y + s * local.x + c * local.y};
  }
};

Frame frame_of(const detail::Xf& xf) {
  return {to_f2(xf.p), to_float(xf.q.c), to_float(xf.q.s)};
}

/// A closed convex outline, counter-clockwise, in the body frame: the
/// shape's core points swept by its radius (a circle is one point, a
/// capsule two), each corner's arc cut into segments of at most one
/// `circle_segments`-th of a turn.
struct Outline {
  static constexpr uint32_t kMax = 64 + 2 * sim2d::kMaxPolygonVertices + 4;
  std::array<F2, kMax> points{};
  uint32_t count = 0;
  void add(F2 p) {
    if (count < kMax) points[count++] = p;
  }
};

void add_arc(Outline& o, F2 center, float radius, float from, float sweep, uint32_t segments) {
  const float step = 2.0f * rwd::kPi / static_cast<float>(segments);
  const uint32_t n = std::max(1u, static_cast<uint32_t>(std::ceil(sweep / step - 1e-4f)));
  for (uint32_t k = 0; k <= n; ++k) {
    const float a = from + sweep * static_cast<float>(k) / static_cast<float>(n);
    o.add(center + F2{rwd::det_cos(a), rwd::det_sin(a)} * radius);
  }
}

Outline outline_of(const Shape2D& shape, uint32_t segments) {
  Outline o;
  const float r = to_float(shape.radius);
  if (shape.type == ShapeType2D::kCircle) {
    const F2 c = to_f2(shape.vertices[0]);
    for (uint32_t k = 0; k < segments; ++k) {
      const float a = 2.0f * rwd::kPi * static_cast<float>(k) / static_cast<float>(segments);
      o.add(c + F2{rwd::det_cos(a), rwd::det_sin(a)} * r);
    }
    return o;
  }
  // Capsules and polygons: the core loop's edge normals, then an arc
  // about each core point from the normal of the edge before it to the
  // normal of the edge after it.
  std::array<F2, sim2d::kMaxPolygonVertices> core{};
  std::array<float, sim2d::kMaxPolygonVertices> normal_angle{};
  const uint32_t m = shape.type == ShapeType2D::kPolygon ? shape.count : 2u;
  for (uint32_t i = 0; i < m; ++i) core[i] = to_f2(shape.vertices[i]);
  for (uint32_t i = 0; i < m; ++i) {
    const F2 d = core[(i + 1) % m] - core[i];
    normal_angle[i] = rwd::det_atan2(-d.x, d.y);  // the right-hand normal (d.y, -d.x)
  }
  for (uint32_t i = 0; i < m; ++i) {
    if (r == 0.0f) {
      o.add(core[i]);
      continue;
    }
    const float before = normal_angle[(i + m - 1) % m];
    float sweep = normal_angle[i] - before;
    while (sweep < 0.0f) sweep += 2.0f * rwd::kPi;
    add_arc(o, core[i], r, before, sweep, segments);
  }
  return o;
}

void draw_local_shape(const Shape2D& shape, const Frame& f, float z, DrawColor color,
                      const DebugDrawOptions& o, DebugDrawBuffers& out) {
  auto line = [&](F2 a, F2 b) {
    const F2 wa = f.world(a);
    const F2 wb = f.world(b);
    out.add_line(wa.x, wa.y, z, wb.x, wb.y, z, color);
  };
  if (shape.type == ShapeType2D::kSegment || shape.type == ShapeType2D::kChainSegment) {
    if (o.shapes || o.solid_shapes) line(to_f2(shape.vertices[0]), to_f2(shape.vertices[1]));
    return;
  }
  const Outline outline = outline_of(shape, o.circle_segments);
  if (o.shapes) {
    for (uint32_t i = 0; i < outline.count; ++i) {
      line(outline.points[i], outline.points[(i + 1) % outline.count]);
    }
    if (shape.type == ShapeType2D::kCircle) {  // the body's x axis through the centre
      const F2 c = to_f2(shape.vertices[0]);
      line(c, c + F2{to_float(shape.radius), 0.0f});
    }
  }
  if (o.solid_shapes) {
    const F2 first = f.world(outline.points[0]);
    for (uint32_t i = 1; i + 1 < outline.count; ++i) {
      const F2 b = f.world(outline.points[i]);
      const F2 c = f.world(outline.points[i + 1]);
      out.triangles.push_back({first.x, first.y, z, color});
      out.triangles.push_back({b.x, b.y, z, color});
      out.triangles.push_back({c.x, c.y, z, color});
    }
  }
}

DrawColor body_color(const BodyRecord2D& body, uint32_t index, const DebugDrawOptions& o) {
  const rwd::DrawColors& c = o.colors;
  if (std::find(o.highlight_bodies.begin(), o.highlight_bodies.end(), index) !=
      o.highlight_bodies.end()) {
    return c.highlight;
  }
  if ((body.flags & kBodyEnabled) == 0) return c.disabled_body;
  if ((body.flags & kBodySensor) != 0) return c.sensor_body;
  if (body.kind == BodyKind2D::kStatic) return c.static_body;
  if (body.kind == BodyKind2D::kKinematic) return c.kinematic_body;
  return (body.flags & kBodyAwake) != 0 ? c.awake_body : c.asleep_body;
}

void line(DebugDrawBuffers& out, F2 a, F2 b, float z, DrawColor color) {
  out.add_line(a.x, a.y, z, b.x, b.y, z, color);
}

void cross_at(DebugDrawBuffers& out, F2 p, float z, float half, DrawColor color) {
  line(out, p - F2{half, 0.0f}, p + F2{half, 0.0f}, z, color);
  line(out, p - F2{0.0f, half}, p + F2{0.0f, half}, z, color);
}

void draw_bodies(const World2DState& s, const DebugDrawOptions& o, DebugDrawBuffers& out) {
  for (uint32_t i = 0; i < s.bodies.size(); ++i) {
    const BodyRecord2D& b = s.bodies[i];
    if ((b.flags & kBodyLive) == 0) continue;
    const float z = to_float(b.z);
    if (b.kind != BodyKind2D::kStatic || o.static_shapes) {
      draw_local_shape(b.shape, frame_of(detail::origin_transform(b)), z, body_color(b, i, o), o,
                       out);
    }
    if (o.centers_of_mass) {
      const F2 c = to_f2(b.center);
      const F2 x{to_float(b.rotation.c), to_float(b.rotation.s)};
      line(out, c, c + x * o.axis_length_m, z, 0xFF3030FFu);
      line(out, c, c + F2{-x.y, x.x} * o.axis_length_m, z, 0x30FF30FFu);
    }
  }
}

void draw_bounds(const World2DState& s, const DebugDrawOptions& o, DebugDrawBuffers& out) {
  for (uint32_t i = 0; i < s.bodies.size(); ++i) {
    const BodyRecord2D& b = s.bodies[i];
    if ((b.flags & kBodyLive) == 0) continue;
    const detail::Box2W box = detail::shape_bounds(b.shape, detail::origin_transform(b));
    const F2 lo = to_f2(box.lower);
    const F2 hi = to_f2(box.upper);
    const float z = to_float(b.z);
    line(out, lo, {hi.x, lo.y}, z, o.colors.bounds);
    line(out, {hi.x, lo.y}, hi, z, o.colors.bounds);
    line(out, hi, {lo.x, hi.y}, z, o.colors.bounds);
    line(out, {lo.x, hi.y}, lo, z, o.colors.bounds);
  }
}

void draw_contacts(const World2DState& s, const DebugDrawOptions& o, DebugDrawBuffers& out) {
  for (const ContactRecord2D& rec : s.contacts) {
    if ((rec.flags & kContactTouching) == 0 || (rec.flags & kContactSensor) != 0) continue;
    const BodyRecord2D& a = s.bodies[rec.a];
    const F2 center = to_f2(a.center);
    const F2 normal = to_f2(rec.normal);
    const float z = std::max(to_float(a.z), to_float(s.bodies[rec.b].z));
    for (uint32_t k = 0; k < rec.count; ++k) {
      const ContactPoint2D& cp = rec.points[k];
      const F2 p = center + to_f2(cp.anchor_a);
      const DrawColor color =
          cp.separation <= 0 ? o.colors.contact_touching : o.colors.contact_speculative;
      out.add_point(p.x, p.y, z, color, o.contact_point_px);
      if (o.contact_normals) {
        line(out, p, p + normal * o.normal_length_m, z, o.colors.contact_normal);
      }
    }
  }
}

void draw_joints(const World2DState& s, const DebugDrawOptions& o, DebugDrawBuffers& out) {
  const float half = 0.25f * o.axis_length_m;
  for (const JointRecord2D& j : s.joints) {
    if ((j.flags & kJointLive) == 0) continue;
    const DrawColor color = (j.flags & kJointBroken) != 0 ? o.colors.joint_broken : o.colors.joint;
    const BodyRecord2D& ba = s.bodies[j.a];
    const BodyRecord2D& bb = s.bodies[j.b];
    const float z = std::max(to_float(ba.z), to_float(bb.z));
    const F2 a = frame_of(detail::origin_transform(ba)).world(to_f2(j.local_anchor_a));
    const F2 b = frame_of(detail::origin_transform(bb)).world(to_f2(j.local_anchor_b));
    if (j.type == JointType2D::kGrab) {  // B's anchor and where it is pulled
      line(out, b, to_f2(j.target), z, color);
      cross_at(out, b, z, half, color);
      cross_at(out, to_f2(j.target), z, half, color);
      continue;
    }
    line(out, to_f2(ba.center), a, z, color);
    line(out, to_f2(bb.center), b, z, color);
    line(out, a, b, z, color);
    cross_at(out, a, z, half, color);
    cross_at(out, b, z, half, color);
  }
}

}  // namespace

void debug_draw(const World2D& world, const DebugDrawOptions& options, DebugDrawBuffers& out) {
  const DebugDrawOptions o = rwd::sanitized(options);
  const World2DState& s = world.state();
  if (o.shapes || o.solid_shapes || o.centers_of_mass) draw_bodies(s, o, out);
  if (o.bounds) draw_bounds(s, o, out);
  if (o.contacts) draw_contacts(s, o, out);
  if (o.joints) draw_joints(s, o, out);
}

rwd::WorldViewStats view_stats(const World2D& world) {
  const World2DState& s = world.state();
  rwd::WorldViewStats v;
  for (const BodyRecord2D& b : s.bodies) {
    if ((b.flags & kBodyLive) == 0) continue;
    ++v.bodies;
    v.awake_bodies += (b.flags & kBodyAwake) != 0 ? 1u : 0u;
  }
  for (const ContactRecord2D& rec : s.contacts) {
    if ((rec.flags & kContactTouching) == 0) continue;
    ++v.touching_pairs;
    v.contact_points += (rec.flags & kContactSensor) == 0 ? rec.count : 0u;
  }
  for (const JointRecord2D& j : s.joints) v.joints += (j.flags & kJointLive) != 0 ? 1u : 0u;
  return v;
}

void draw_shape(const Shape2D& shape, Vec2 position, Fx angle, Fx z, DrawColor color,
                const DebugDrawOptions& options, DebugDrawBuffers& out) {
  if (!validate_shape(shape).ok()) return;
  const DebugDrawOptions o = rwd::sanitized(options);
  const detail::Xf xf{detail::V2{detail::w_from(position.x), detail::w_from(position.y)},
                      detail::rotation_from_angle(angle)};
  draw_local_shape(shape, frame_of(xf), to_float(z), color, o, out);
}

}  // namespace rwd::sim2d
