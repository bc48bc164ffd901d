// SPDX-License-Identifier: MIT
// The compound: registered convex children (compound.h) in the body's mass
// frame. Each child meets the other shape through the collide table, and
// the children's manifolds are grouped by normal: the deepest child leads
// the first group, every child within 30 degrees of a group's leader joins
// it (the first such group), and a child no group takes leads a new one,
// up to kMaxContactParts (a child beyond them is dropped). Each group is
// one manifold, the body pair's contact record of that part: the leader's
// normal, its members' points measured along it, reduced to four as
// triangle contacts are (manifold_triangles.h). So a table wedged between
// the floor and a wall keeps both contacts. Feature ids mix the child
// index into the child's id, so they persist while the same children touch.
#include <algorithm>
#include <bit>
#include <string>

#include "d3/aabb_tree.h"
#include "d3/body_storage.h"
#include "d3/compound.h"
#include "d3/compound_contact.h"
#include "d3/manifold.h"
#include "d3/manifold_triangles.h"
#include "d3/shape_ops.h"

namespace rwd::sim::d3 {
namespace {

const Compound& compound_of(const Shape& s, const GeometryStore& store) {
  return *store.compound(s.geometry);
}

// A child's pose in the world, for a compound whose mass frame is at `pose`.
ShapePose child_pose(const ShapePose& pose, const CompoundPart& part) {
  ShapePose p;
  p.position = pose.position + pose.axes * part.position;
  p.rotation = normalize(pose.rotation * part.rotation);
  p.axes = mat3_from_quat(p.rotation);
  return p;
}

Status check(const Shape& s, const GeometryStore& store) {
  if (store.compound(s.geometry) == nullptr) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "compound shape refers to geometry " + std::to_string(s.geometry) +
                             ", which is not a compound in this world's geometry store");
  }
  return Status::Ok();
}

void canonical(Shape& s, const GeometryStore& store) {
  s.radius = 0.0f;
  s.half_height = 0.0f;
  s.half_extents = compound_of(s, store).half_size;
}

float extent(const Shape& s, const GeometryStore& store) {
  return compound_of(s, store).extent;
}

float volume(const Shape& s, const GeometryStore& store) {
  return compound_of(s, store).volume;
}

Vec3 inertia(const Shape& s, const GeometryStore& store, float mass) {
  return compound_of(s, store).unit_inertia * mass;
}

Vec3 half_bounds(const Shape& s, const Mat3& axes) {
  const Vec3 h = s.half_extents;
  return abs(axes.c0) * h.x + abs(axes.c1) * h.y + abs(axes.c2) * h.z;
}

// The nearest child hit (ties to the lower child).
bool raycast(const Shape& s, const GeometryStore& store, Vec3 position, Quat rotation, Vec3 origin,
             Vec3 dir, float max_distance, float& t, Vec3& normal) {
  const ShapePose pose{position, rotation, mat3_from_quat(rotation)};
  bool hit = false;
  float best = max_distance;
  for (const CompoundPart& part : compound_of(s, store).parts) {
    const ShapePose p = child_pose(pose, part);
    float ct = 0.0f;
    Vec3 cn;
    if (shape_ops(part.shape.type)
            .raycast(part.shape, store, p.position, p.rotation, origin, dir, best, ct, cn) &&
        (!hit || ct < best)) {
      hit = true;
      best = ct;
      normal = cn;
    }
  }
  t = best;
  return hit;
}

// The earliest child hit (ties to the lower child).
ShapeCastOutput sweep(const Shape& s, const GeometryStore& store, Vec3 position, const Mat3& axes,
                      const ConvexProxy& swept, Vec3 translation, float max_fraction) {
  ShapePose pose;
  pose.position = position;
  pose.axes = axes;
  ShapeCastOutput best;
  float reach = max_fraction;
  for (const CompoundPart& part : compound_of(s, store).parts) {
    // The child's axes from the compound's matrix (no quaternion needed).
    const Mat3 child = mat3_from_quat(part.rotation);
    const Mat3 world{axes * child.c0, axes * child.c1, axes * child.c2};
    const ShapeCastOutput hit = shape_ops(part.shape.type)
                                    .sweep(part.shape, store, position + axes * part.position,
                                           world, swept, translation, reach);
    if (hit.hit && (!best.hit || hit.fraction < best.fraction)) {
      best = hit;
      reach = hit.fraction;
    }
  }
  return best;
}

}  // namespace

void place_children(const Shape& s, const ShapePose& pose, const GeometryStore& store,
                    ChildFrame frames[kCompoundMaxChildren]) {
  const Compound& c = compound_of(s, store);
  for (uint32_t i = 0; i < c.parts.size(); ++i) {
    frames[i].pose = child_pose(pose, c.parts[i]);
    frames[i].bounds = shape_aabb(c.parts[i].shape, frames[i].pose.position, frames[i].pose.axes);
  }
}

uint32_t collide_compound_parts(const Shape& a, const ChildFrame* frames_a, const Shape& b,
                                const ShapePose& pb, const ChildFrame* frames_b,
                                float speculative_m, const GeometryStore& store, CompoundWork& work,
                                Manifold out[kMaxContactParts]) {
  const Compound& c = compound_of(a, store);
  // Each child of A against B, or against each child of B when B is a
  // compound too (every child pair is its own contact: a compound B would
  // answer a child of A with its deepest group alone). At most
  // kCompoundMaxChildren child contacts are kept, the deepest (ties to the
  // earlier pair).
  const Compound* cb = b.type == ShapeType::kCompound ? &compound_of(b, store) : nullptr;
  const uint32_t b_count = cb != nullptr ? static_cast<uint32_t>(cb->parts.size()) : 1u;
  Manifold* children = work.children;
  float* deepest = work.deepest;
  uint32_t* keys = work.keys;
  uint32_t* order = work.order;
  uint32_t touching = 0;
  Manifold contact;
  // Each side's children with their bounds grown by the speculative
  // distance: a child pair whose grown bounds miss is not collided, as the
  // broadphase does not pair bodies whose grown bounds miss
  // (find_pairs.cpp), so a compound's far children cost nothing.
  const auto grown = [speculative_m](Aabb box) {
    box.lower -= Vec3{speculative_m, speculative_m, speculative_m};
    box.upper += Vec3{speculative_m, speculative_m, speculative_m};
    return box;
  };
  Aabb* bounds_b = work.grown_b;
  if (cb != nullptr) {
    for (uint32_t j = 0; j < b_count; ++j) bounds_b[j] = grown(frames_b[j].bounds);
  } else {
    bounds_b[0] = grown(shape_aabb(b, pb.position, pb.axes));
  }
  for (uint32_t i = 0; i < c.parts.size(); ++i) {
    const ShapePose& child_a = frames_a[i].pose;
    const Aabb bounds_a = grown(frames_a[i].bounds);
    // Which of B's children the child's bounds meet, as bits, without a
    // branch per test (most tests miss, at random); then those in order.
    uint32_t meets = 0;
    for (uint32_t j = 0; j < b_count; ++j) {
      const Aabb& o = bounds_b[j];
      const bool hit = (bounds_a.lower.x <= o.upper.x) & (o.lower.x <= bounds_a.upper.x) &
                       (bounds_a.lower.y <= o.upper.y) & (o.lower.y <= bounds_a.upper.y) &
                       (bounds_a.lower.z <= o.upper.z) & (o.lower.z <= bounds_a.upper.z);
      meets |= static_cast<uint32_t>(hit) << j;
    }
    for (; meets != 0; meets &= meets - 1) {
      const auto j = static_cast<uint32_t>(std::countr_zero(meets));
      collide_shapes(c.parts[i].shape, child_a, cb != nullptr ? cb->parts[j].shape : b,
                     cb != nullptr ? frames_b[j].pose : pb, speculative_m, contact, &store);
      if (contact.point_count == 0) continue;
      float low = contact.points[0].separation;
      for (uint32_t k = 1; k < contact.point_count; ++k) {
        if (contact.points[k].separation < low) low = contact.points[k].separation;
      }
      uint32_t slot = touching;
      if (touching == kCompoundMaxChildren) {
        // Full: the shallowest gives way to a deeper one.
        slot = 0;
        for (uint32_t t = 1; t < touching; ++t) {
          if (deepest[t] >= deepest[slot]) slot = t;
        }
        if (!(low < deepest[slot])) continue;
      } else {
        ++touching;
      }
      children[slot] = contact;
      deepest[slot] = low;
      keys[slot] = cb != nullptr ? (i << 27) ^ (j << 23) : (i << 27);
    }
  }
  for (uint32_t t = 0; t < touching; ++t) order[t] = t;
  // Deepest child contact first (ties to the lower key): it leads the
  // first group, as the deepest child's normal led the single manifold.
  std::sort(order, order + touching, [&](uint32_t x, uint32_t y) {
    return deepest[x] < deepest[y] || (deepest[x] == deepest[y] && keys[x] < keys[y]);
  });
  uint32_t* group_of = work.group_of;
  static_assert(kCompoundMaxChildren <= 16, "child indices take four bits of a feature id");
  uint32_t groups = 0;
  for (uint32_t n = 0; n < touching; ++n) {
    const uint32_t i = order[n];
    group_of[i] = kMaxContactParts;  // dropped, unless a group takes it
    for (uint32_t g = 0; g < groups; ++g) {
      if (dot(children[i].normal, out[g].normal) >= kBlendCos) {
        group_of[i] = g;
        break;
      }
    }
    if (group_of[i] == kMaxContactParts && groups < kMaxContactParts) {
      group_of[i] = groups;
      out[groups++].normal = children[i].normal;
    }
  }
  // Each group's points, measured along its leader's normal, reduced to
  // four as triangle contacts are.
  TrianglePoint* points = work.points;
  for (uint32_t g = 0; g < groups; ++g) {
    Manifold& m = out[g];
    const Vec3 normal = m.normal;
    uint32_t n = 0;
    for (uint32_t t = 0; t < touching; ++t) {
      const uint32_t i = order[t];
      if (group_of[i] != g) continue;
      const float cos = dot(children[i].normal, normal);
      for (uint32_t k = 0; k < children[i].point_count; ++k) {
        const ManifoldPoint& p = children[i].points[k];
        points[n++] = {p.point, p.separation * cos, keys[i] ^ p.feature_id};
      }
    }
    uint32_t chosen[4];
    const uint32_t kept = reduce_triangle_points(points, n, normal, chosen);
    m.separating_axis = kNoSeparatingAxis;
    for (uint32_t k = 0; k < kept; ++k) {
      ManifoldPoint& mp = m.points[k];
      mp.point = points[chosen[k]].point;
      mp.separation = points[chosen[k]].separation;
      mp.feature_id = points[chosen[k]].feature_id;
    }
    m.point_count = kept;
  }
  return groups;
}

void collide_compound(const Shape& a, const ShapePose& pa, const Shape& b, const ShapePose& pb,
                      float speculative_m, const GeometryStore& store, Manifold& out) {
  Manifold parts[kMaxContactParts];
  out.point_count = 0;
  out.separating_axis = kNoSeparatingAxis;
  out.normal = {0.0f, 1.0f, 0.0f};
  CompoundWork work;
  place_children(a, pa, store, work.frames_a);
  const bool b_compound = b.type == ShapeType::kCompound;
  if (b_compound) place_children(b, pb, store, work.frames_b);
  if (collide_compound_parts(a, work.frames_a, b, pb, b_compound ? work.frames_b : nullptr,
                             speculative_m, store, work, parts) == 0) {
    return;
  }
  out = parts[0];
}

extern const ShapeOps kCompoundOps{"compound", true,        check,   canonical, extent, volume,
                                   inertia,    half_bounds, raycast, nullptr,   sweep,  nullptr};

}  // namespace rwd::sim::d3
