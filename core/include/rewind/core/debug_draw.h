// SPDX-License-Identifier: MIT
#pragma once
// Debug draw, the part both lanes share: plain buffers of lines, triangles
// and points with colours, which any renderer draws (a browser's WebGL, an
// editor's immediate mode, an image for a test), and the options that say
// what to put in them. The engine has no renderer: World3D's and World2D's
// debug_draw() (rewind/sim/debug_draw3d.h, rewind/sim2d/debug_draw2d.h)
// only fill these buffers from a world's state.
//
// Drawing reads the world and changes nothing: it is no part of the state,
// its checksum or its snapshots, and it may run between any two steps.
// The buffers are float32 because they are for the eye; no value drawn is
// ever read back into a simulation.
#include <cstdint>
#include <span>
#include <vector>

namespace rwd {

/// A colour as 0xRRGGBBAA (red in the high byte, alpha in the low one).
using DrawColor = uint32_t;

/// One vertex of a line or triangle: metres, world frame (2D worlds draw
/// at z = the body's draw order, World2D::z), and its colour.
struct DrawVertex {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
  DrawColor color = 0;
};

/// One point: where (m, world frame), its colour and its size on screen in
/// pixels.
struct DrawPoint {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
  DrawColor color = 0;
  float size_px = 1.0f;
};

/// What a debug draw made. `lines` holds two vertices per segment,
/// `triangles` three per triangle (counter-clockwise seen from outside a
/// solid). A call appends; clear() between frames, so the vectors keep
/// their capacity and a warm frame allocates nothing.
struct DebugDrawBuffers {
  std::vector<DrawVertex> lines;
  std::vector<DrawVertex> triangles;
  std::vector<DrawPoint> points;

  void clear() {
    lines.clear();
    triangles.clear();
    points.clear();
  }
  bool empty() const { return lines.empty() && triangles.empty() && points.empty(); }
  void add_line(float ax, float ay, float az, float bx, float by, float bz, DrawColor color) {
    lines.push_back({ax, ay, az, color});
    lines.push_back({bx, by, bz, color});
  }
  void add_point(float x, float y, float z, DrawColor color, float size_px) {
    points.push_back({x, y, z, color, size_px});
  }
};

/// The colours of a debug draw. A body's outline takes the first that
/// applies: highlight, disabled, sensor, static, kinematic, asleep, awake.
struct DrawColors {
  DrawColor static_body = 0x8A9BA8FFu;          ///< slate grey
  DrawColor kinematic_body = 0x4A90E2FFu;       ///< blue
  DrawColor awake_body = 0xF5A623FFu;           ///< orange
  DrawColor asleep_body = 0x9B8AC4FFu;          ///< lavender
  DrawColor disabled_body = 0x4D4D4DFFu;        ///< dark grey: out of the simulation
  DrawColor sensor_body = 0xE8D44DFFu;          ///< yellow
  DrawColor highlight = 0xFF2D2DFFu;            ///< red: DebugDrawOptions::highlight_bodies
  DrawColor contact_touching = 0x3CDC50FFu;     ///< green: separation <= 0
  DrawColor contact_speculative = 0x7F7F7FFFu;  ///< grey: a point still apart
  DrawColor contact_normal = 0xFFFFFFFFu;       ///< white
  DrawColor joint = 0x2EC4B6FFu;                ///< teal
  DrawColor joint_broken = 0x8C3030FFu;         ///< dark red
  DrawColor bounds = 0xC8C8C8FFu;               ///< light grey
};

/// What a debug draw of a world includes. The defaults draw every body's
/// outline, the last step's contact points with their normals and the
/// joints; bounds, solids and centres of mass are on request.
struct DebugDrawOptions {
  bool shapes = true;            ///< each body's outline (lines)
  bool solid_shapes = false;     ///< each body's surface as triangles as well
  bool static_shapes = true;     ///< false: leave static bodies out (a viewer caches them)
  bool contacts = true;          ///< contact points of the last step
  bool contact_normals = true;   ///< and their normals, as lines
  bool joints = true;            ///< a line between each joint's anchors, a cross at each
  bool bounds = false;           ///< each body's world-axis bounds (the broadphase's, not fattened)
  bool centers_of_mass = false;  ///< a small frame at each body's centre of mass
  float normal_length_m = 0.25f;  ///< length of a drawn contact normal, m (> 0)
  float axis_length_m = 0.2f;     ///< length of a centre of mass frame's axes, m (> 0)
  float contact_point_px = 6.0f;  ///< size of a drawn contact point, pixels
  /// Curved outlines (spheres, circles, capsules' ends) are drawn as this
  /// many segments per full turn, 8 to 64.
  uint32_t circle_segments = 24;
  /// Bodies drawn in `colors.highlight` whatever their state, by slot index
  /// (BodyId::index, BodyId2D::index): the bodies of a desync report, a
  /// selection. Read during the call only.
  std::span<const uint32_t> highlight_bodies;
  DrawColors colors;
};

/// What a viewer shows of a world beside its drawing: counts as of the last
/// step (a viewer adds its own step time).
struct WorldViewStats {
  uint32_t bodies = 0;          ///< live bodies, static ones included
  uint32_t awake_bodies = 0;    ///< simulated in the last step
  uint32_t touching_pairs = 0;  ///< body pairs in contact (solid or sensor)
  uint32_t contact_points = 0;  ///< manifold points of the solid ones
  uint32_t joints = 0;          ///< live joints, broken ones included
};

/// Clamps options to their ranges (circle_segments to [8, 64], non-finite
/// or non-positive lengths to their defaults): a draw never refuses.
inline DebugDrawOptions sanitized(DebugDrawOptions o) {
  const DebugDrawOptions d;
  if (o.circle_segments < 8) o.circle_segments = 8;
  if (o.circle_segments > 64) o.circle_segments = 64;
  if (!(o.normal_length_m > 0.0f && o.normal_length_m < 1e6f))
    o.normal_length_m = d.normal_length_m;
  if (!(o.axis_length_m > 0.0f && o.axis_length_m < 1e6f)) o.axis_length_m = d.axis_length_m;
  if (!(o.contact_point_px > 0.0f && o.contact_point_px < 1e4f))
    o.contact_point_px = d.contact_point_px;
  return o;
}

}  // namespace rwd
