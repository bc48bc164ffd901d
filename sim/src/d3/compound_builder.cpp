// SPDX-License-Identifier: MIT
// Builds a compound from its children: each child's own mass frame placed
// in the compound's authored frame, then the whole's centre of mass (by
// child volume, uniform density) and inertia (each child's principal
// inertia turned into the common frame, moved by the parallel-axis
// theorem), diagonalized by the hull builder's Jacobi rotations. Sums run
// in double, children in the order given, so the result is a pure function
// of the input bits.
#include "d3/compound_builder.h"

#include <cmath>
#include <string>

#include "d3/body_storage.h"
#include "d3/hull_build_steps.h"
#include "d3/mass_frame.h"
#include "d3/shape_ops.h"
#include "d3/state_rules.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim::d3 {
namespace {

using hull_steps::DVec3;

Status refuse(size_t child, const std::string& why) {
  return Status::Error(ErrorCode::kInvalidArgument,
                       "compound child " + std::to_string(child) + ": " + why);
}

DVec3 to_d(Vec3 v) {
  return {v.x, v.y, v.z};
}

// The child as a body would take it: sizes on the canonical grid, checked,
// canonical; its pose on the grid; and its mass frame's pose.
Status place_child(const CompoundChild& in, size_t index, const GeometryStore& store,
                   CompoundPart& part) {
  const ShapeType t = in.shape.type;
  if (t != ShapeType::kSphere && t != ShapeType::kBox && t != ShapeType::kCapsule &&
      t != ShapeType::kHull) {
    return refuse(index, "only spheres, boxes, capsules and hulls can be children");
  }
  Shape shape = in.shape;
  shape.radius = quantize(in.shape.radius);
  shape.half_extents = quantize(in.shape.half_extents);
  shape.half_height = quantize(in.shape.half_height);
  if (Status s = check_shape(shape, store); !s.ok()) return refuse(index, s.message());
  shape_ops(t).canonical(shape, store);
  if (!is_finite(in.position) || std::fabs(in.position.x) > 1000.0f ||
      std::fabs(in.position.y) > 1000.0f || std::fabs(in.position.z) > 1000.0f) {
    return refuse(index, "position must be finite, within 1000 m of the origin");
  }
  if (!is_finite(in.rotation) || length_squared(in.rotation) < 1e-6f) {
    return refuse(index, "rotation must be a finite, non-zero quaternion");
  }
  part.shape = shape;
  const Quat q = normalize(in.rotation);
  const Quat on_grid{quantize(q.x), quantize(q.y), quantize(q.z), quantize(q.w)};
  authored_to_mass(mass_frame(shape, store), quantize(in.position), on_grid, part.position,
                   part.rotation);
  return Status::Ok();
}

}  // namespace

Result<Compound> build_compound(std::span<const CompoundChild> children,
                                const GeometryStore& store) {
  if (children.empty() || children.size() > kCompoundMaxChildren) {
    return Status::Error(
        ErrorCode::kInvalidArgument,
        "a compound has 1 to " + std::to_string(kCompoundMaxChildren) + " children");
  }
  Compound c;
  c.parts.resize(children.size());
  double volume = 0.0;
  DVec3 weighted;
  for (size_t i = 0; i < children.size(); ++i) {
    if (Status s = place_child(children[i], i, store, c.parts[i]); !s.ok()) return s;
    const double v = shape_ops(c.parts[i].shape.type).volume(c.parts[i].shape, store);
    volume += v;
    weighted = weighted + to_d(c.parts[i].position) * v;
  }
  if (!(volume > 1e-12)) {
    return Status::Error(ErrorCode::kInvalidArgument, "compound has no volume");
  }
  const DVec3 center = weighted * (1.0 / volume);
  // Inertia per kilogram of the whole about its centre of mass.
  double tensor[3][3] = {};
  for (const CompoundPart& p : c.parts) {
    const double share = shape_ops(p.shape.type).volume(p.shape, store) / volume;
    const Vec3 u = shape_ops(p.shape.type).inertia(p.shape, store, 1.0f);
    const Mat3 r = mat3_from_quat(p.rotation);
    const DVec3 cols[3] = {to_d(r.c0), to_d(r.c1), to_d(r.c2)};
    const double moments[3] = {u.x, u.y, u.z};
    const DVec3 d = to_d(p.position) - center;
    const double dd = hull_steps::dot(d, d);
    const double dv[3] = {d.x, d.y, d.z};
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) {
        // R diag(u) R^T: sum over k of R[row][k] u_k R[col][k].
        double turned = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double rk[3] = {cols[k].x, cols[k].y, cols[k].z};
          turned += rk[row] * moments[k] * rk[col];
        }
        const double shift = (row == col ? dd : 0.0) - dv[row] * dv[col];
        tensor[row][col] += share * (turned + shift);
      }
    }
  }
  const hull_steps::PrincipalAxes principal = hull_steps::principal_axes(tensor);
  const Quat q = hull_steps::quat_from_axes(principal.axes);
  c.frame.center = {static_cast<float>(center.x), static_cast<float>(center.y),
                    static_cast<float>(center.z)};
  c.frame.rotation = q;
  c.volume = static_cast<float>(volume);
  c.unit_inertia = {static_cast<float>(principal.moments[0]),
                    static_cast<float>(principal.moments[1]),
                    static_cast<float>(principal.moments[2])};
  Vec3 lo{1e30f, 1e30f, 1e30f};
  Vec3 hi{-1e30f, -1e30f, -1e30f};
  for (CompoundPart& p : c.parts) {
    p.position = inv_rotate(q, p.position - c.frame.center);
    p.rotation = normalize(conjugate(q) * p.rotation);
    const Aabb box = shape_aabb(p.shape, p.position, mat3_from_quat(p.rotation));
    lo = min(lo, box.lower);
    hi = max(hi, box.upper);
    const float reach = length(p.position) + shape_ops(p.shape.type).extent(p.shape, store);
    if (reach > c.extent) c.extent = reach;
  }
  c.half_size = max(abs(lo), abs(hi));
  return c;
}

}  // namespace rwd::sim::d3
