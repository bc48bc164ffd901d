// SPDX-License-Identifier: MIT
#include "d3/draw_shapes3d.h"

#include <array>

#include "d3/compound.h"
#include "d3/height_field.h"
#include "d3/hull.h"
#include "d3/mass_frame.h"
#include "d3/mesh.h"
#include "rewind/core/det_math.h"

namespace rwd::sim::d3 {
namespace {

/// Appends lines and triangles given in a shape's frame, placed at a pose.
class Pen {
 public:
  Pen(DebugDrawBuffers& out, Vec3 position, Quat rotation, DrawColor color)
      : out_(out), position_(position), axes_(mat3_from_quat(rotation)), color_(color) {}

  Vec3 world(Vec3 local) const { return position_ + axes_ * local; }
  void line(Vec3 a, Vec3 b) {
    const Vec3 wa = world(a);
    const Vec3 wb = world(b);
    out_.add_line(wa.x, wa.y, wa.z, wb.x, wb.y, wb.z, color_);
  }
  void triangle(Vec3 a, Vec3 b, Vec3 c) {
    for (const Vec3 p : {a, b, c}) {
      const Vec3 w = world(p);
      out_.triangles.push_back({w.x, w.y, w.z, color_});
    }
  }

 private:
  DebugDrawBuffers& out_;
  Vec3 position_;
  Mat3 axes_;
  DrawColor color_;
};

/// cos and sin of segment k of n (k in [0, n]; k = n repeats k = 0 exactly,
/// so closed curves close without a seam).
struct UnitCircle {
  explicit UnitCircle(uint32_t n) : count(n) {
    for (uint32_t k = 0; k < n; ++k) {
      const float a = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(n);
      c[k] = det_cos(a);
      s[k] = det_sin(a);
    }
    c[n] = c[0];
    s[n] = s[0];
  }
  uint32_t count;
  std::array<float, 65> c{};
  std::array<float, 65> s{};
};

/// A circle of radius r about `center` in the plane of unit axes u, v.
void circle(Pen& pen, const UnitCircle& uc, Vec3 center, Vec3 u, Vec3 v, float r, uint32_t from,
            uint32_t to) {
  for (uint32_t k = from; k < to; ++k) {
    pen.line(center + (u * uc.c[k] + v * uc.s[k]) * r,
             center + (u * uc.c[k + 1] + v * uc.s[k + 1]) * r);
  }
}

const Vec3 kX{1.0f, 0.0f, 0.0f};
const Vec3 kY{0.0f, 1.0f, 0.0f};
const Vec3 kZ{0.0f, 0.0f, 1.0f};

/// A sphere (half_height 0) or a capsule along y: outline. A sphere draws
/// its three great circles in the body's planes, so its turning shows.
void round_lines(Pen& pen, const UnitCircle& uc, float r, float h) {
  const uint32_t n = uc.count;
  if (h == 0.0f) {
    circle(pen, uc, {}, kX, kY, r, 0, n);
    circle(pen, uc, {}, kY, kZ, r, 0, n);
    circle(pen, uc, {}, kZ, kX, r, 0, n);
    return;
  }
  const Vec3 top{0.0f, h, 0.0f};
  circle(pen, uc, top, kZ, kX, r, 0, n);
  circle(pen, uc, -top, kZ, kX, r, 0, n);
  for (const Vec3 side : {kX, kZ, -kX, -kZ}) pen.line(side * r - top, side * r + top);
  // The caps: half circles in the xy and zy planes (n is even).
  circle(pen, uc, top, kX, kY, r, 0, n / 2);
  circle(pen, uc, -top, kX, kY, r, n / 2, n);
  circle(pen, uc, top, kZ, kY, r, 0, n / 2);
  circle(pen, uc, -top, kZ, kY, r, n / 2, n);
}

/// A sphere or a capsule along y: surface, rings of latitude from the
/// bottom pole to the top one (the capsule's cylinder between its two
/// equators), counter-clockwise seen from outside.
void round_triangles(Pen& pen, const UnitCircle& uc, float r, float h) {
  const uint32_t n = uc.count;
  const uint32_t half = n / 4;  // rings per hemisphere, pole to equator
  std::array<float, 40> ring_y{};
  std::array<float, 40> ring_r{};
  uint32_t rings = 0;
  for (uint32_t k = 0; k <= half; ++k) {  // the bottom hemisphere, its equator last
    const float lat = -0.5f * kPi + 0.5f * kPi * static_cast<float>(k) / static_cast<float>(half);
    ring_y[rings] = -h + r * det_sin(lat);
    ring_r[rings++] = r * det_cos(lat);
  }
  for (uint32_t k = (h == 0.0f ? 1 : 0); k <= half; ++k) {  // the top one, its equator first
    const float lat = 0.5f * kPi * static_cast<float>(k) / static_cast<float>(half);
    ring_y[rings] = h + r * det_sin(lat);
    ring_r[rings++] = r * det_cos(lat);
  }
  ring_r[0] = 0.0f;  // the poles exactly
  ring_r[rings - 1] = 0.0f;
  auto at = [&](uint32_t ring, uint32_t k) {
    return Vec3{ring_r[ring] * uc.c[k], ring_y[ring], ring_r[ring] * uc.s[k]};
  };
  for (uint32_t i = 0; i + 1 < rings; ++i) {
    for (uint32_t k = 0; k < n; ++k) {
      if (ring_r[i] != 0.0f) pen.triangle(at(i, k), at(i + 1, k), at(i, k + 1));
      if (ring_r[i + 1] != 0.0f) pen.triangle(at(i, k + 1), at(i + 1, k), at(i + 1, k + 1));
    }
  }
}

void box_shape(Pen& pen, Vec3 e, bool lines, bool solid) {
  if (lines) {
    for (int axis = 0; axis < 3; ++axis) {  // four edges along each axis
      const Vec3 d = axis == 0 ? kX : axis == 1 ? kY : kZ;
      const Vec3 u = axis == 0 ? kY : axis == 1 ? kZ : kX;
      const Vec3 v = axis == 0 ? kZ : axis == 1 ? kX : kY;
      const float de = component(e, axis);
      const float ue = component(e, (axis + 1) % 3);
      const float ve = component(e, (axis + 2) % 3);
      for (const float su : {-1.0f, 1.0f}) {
        for (const float sv : {-1.0f, 1.0f}) {
          const Vec3 base = u * (su * ue) + v * (sv * ve);
          pen.line(base - d * de, base + d * de);
        }
      }
    }
  }
  if (!solid) return;
  for (int axis = 0; axis < 3; ++axis) {
    const Vec3 n = axis == 0 ? kX : axis == 1 ? kY : kZ;
    const Vec3 u = axis == 0 ? kY : axis == 1 ? kZ : kX;  // u x v = n
    const Vec3 v = axis == 0 ? kZ : axis == 1 ? kX : kY;
    const float ne = component(e, axis);
    const float ue = component(e, (axis + 1) % 3);
    const float ve = component(e, (axis + 2) % 3);
    for (const float side : {1.0f, -1.0f}) {
      const Vec3 c = n * (side * ne);
      const Vec3 a = u * ue;
      const Vec3 b = v * (side * ve);  // the far face winds the other way
      pen.triangle(c - a - b, c + a - b, c + a + b);
      pen.triangle(c - a - b, c + a + b, c - a + b);
    }
  }
}

void hull_shape(Pen& pen, const Hull& hull, bool lines, bool solid) {
  if (lines) {
    for (const HullEdge& e : hull.edges) pen.line(hull.vertices[e.v0], hull.vertices[e.v1]);
  }
  if (!solid) return;
  for (const HullFace& f : hull.faces) {  // each face's loop as a fan
    const Vec3 first = hull.vertices[hull.face_vertices[f.first]];
    for (uint32_t k = 1; k + 1 < f.count; ++k) {
      pen.triangle(first, hull.vertices[hull.face_vertices[f.first + k]],
                   hull.vertices[hull.face_vertices[f.first + k + 1]]);
    }
  }
}

void mesh_shape(Pen& pen, const TriangleMesh& mesh, bool lines, bool solid) {
  for (const MeshTriangle& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t.v[0]];
    const Vec3 b = mesh.vertices[t.v[1]];
    const Vec3 c = mesh.vertices[t.v[2]];
    if (lines) {
      pen.line(a, b);
      pen.line(b, c);
      pen.line(c, a);
    }
    if (solid) pen.triangle(a, b, c);
  }
}

/// Each cell that is not a hole: its two triangles' edges, each edge drawn
/// once (a cell draws its left and top edges and its diagonal; the right
/// and bottom ones only where no cell beyond will).
void height_field_shape(Pen& pen, const HeightField& hf, bool lines, bool solid) {
  const uint32_t cells_x = hf.cols - 1;
  const uint32_t cells_z = hf.rows - 1;
  auto hole = [&](uint32_t r, uint32_t c) {
    return r >= cells_z || c >= cells_x || height_field_is_hole(hf, r * cells_x + c);
  };
  for (uint32_t r = 0; r < cells_z; ++r) {
    for (uint32_t c = 0; c < cells_x; ++c) {
      if (hole(r, c)) continue;
      const Vec3 p00 = height_field_point(hf, r, c);
      const Vec3 p01 = height_field_point(hf, r, c + 1);
      const Vec3 p10 = height_field_point(hf, r + 1, c);
      const Vec3 p11 = height_field_point(hf, r + 1, c + 1);
      if (lines) {
        if (r == 0 || hole(r - 1, c)) pen.line(p00, p01);
        if (c == 0 || hole(r, c - 1)) pen.line(p00, p10);
        pen.line(p00, p11);
        pen.line(p01, p11);  // the right edge, shared with the cell at c + 1
        pen.line(p10, p11);  // the bottom edge, shared with the cell at r + 1
      }
      if (solid) {  // height_field_corners' two halves, facing +y
        pen.triangle(p00, p10, p11);
        pen.triangle(p00, p11, p01);
      }
    }
  }
}

void convex_shape(const GeometryStore& store, const Shape& shape, Vec3 position, Quat rotation,
                  DrawColor color, const DebugDrawOptions& o, const UnitCircle& uc,
                  DebugDrawBuffers& out) {
  Pen pen(out, position, rotation, color);
  switch (shape.type) {
    case ShapeType::kSphere:
    case ShapeType::kCapsule: {
      const float h = shape.type == ShapeType::kCapsule ? shape.half_height : 0.0f;
      if (o.shapes) round_lines(pen, uc, shape.radius, h);
      if (o.solid_shapes) round_triangles(pen, uc, shape.radius, h);
      return;
    }
    case ShapeType::kBox:
      box_shape(pen, shape.half_extents, o.shapes, o.solid_shapes);
      return;
    case ShapeType::kHull:
      if (const Hull* hull = store.hull(shape.geometry)) {
        hull_shape(pen, *hull, o.shapes, o.solid_shapes);
      }
      return;
    case ShapeType::kMesh:
    case ShapeType::kHeightField:
    case ShapeType::kCompound:
      return;  // not a compound's child
  }
}

}  // namespace

void draw_shape_mass_frame(const GeometryStore& store, const Shape& shape, Vec3 position,
                           Quat rotation, DrawColor color, const DebugDrawOptions& o,
                           DebugDrawBuffers& out) {
  if (!o.shapes && !o.solid_shapes) return;
  if (!is_finite(position) || !is_finite(rotation)) return;
  const UnitCircle uc(o.circle_segments & ~3u);  // a multiple of 4: whole hemispheres
  switch (shape.type) {
    case ShapeType::kMesh:
    case ShapeType::kHeightField: {
      if (shape.type == ShapeType::kMesh ? store.mesh(shape.geometry) == nullptr
                                         : store.height_field(shape.geometry) == nullptr) {
        return;
      }
      Vec3 origin;
      Quat turn;
      mass_to_authored(mass_frame(shape, store), position, rotation, origin, turn);
      Pen pen(out, origin, turn, color);
      if (shape.type == ShapeType::kMesh) {
        mesh_shape(pen, *store.mesh(shape.geometry), o.shapes, o.solid_shapes);
      } else {
        height_field_shape(pen, *store.height_field(shape.geometry), o.shapes, o.solid_shapes);
      }
      return;
    }
    case ShapeType::kCompound: {
      const Compound* compound = store.compound(shape.geometry);
      if (compound == nullptr) return;
      for (const CompoundPart& part : compound->parts) {
        convex_shape(store, part.shape, position + rotate(rotation, part.position),
                     rotation * part.rotation, color, o, uc, out);
      }
      return;
    }
    case ShapeType::kSphere:
    case ShapeType::kBox:
    case ShapeType::kCapsule:
    case ShapeType::kHull:
      convex_shape(store, shape, position, rotation, color, o, uc, out);
      return;
  }
}

void draw_box_edges(Vec3 lower, Vec3 upper, DrawColor color, DebugDrawBuffers& out) {
  Pen pen(out, (lower + upper) * 0.5f, Quat{}, color);
  box_shape(pen, (upper - lower) * 0.5f, true, false);
}

}  // namespace rwd::sim::d3
