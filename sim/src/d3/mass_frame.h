// SPDX-License-Identifier: MIT
#pragma once
// A body's two frames. The simulation keeps every body at its centre of
// mass, turned to its principal axes (the mass frame), so the solver sees
// a diagonal inertia for every shape. The game places a body by the
// origin and axes it authored the shape in. For spheres, boxes and
// capsules the two are the same; a hull's mass frame sits where its
// registration found it (HullFrame). The API converts at its edge, so
// state holds mass-frame poses only.
#include "d3/compound.h"
#include "d3/height_field.h"
#include "d3/hull.h"
#include "d3/mesh.h"
#include "rewind/sim/geometry.h"
#include "rewind/sim/shape.h"
#include "rewind/sim/world_state.h"

namespace rwd::sim::d3 {

/// Where a shape's mass frame sits in its authored frame.
struct MassFrame {
  Vec3 center;    ///< metres, in the authored frame
  Quat rotation;  ///< mass-frame axes in the authored frame
  bool identity = true;
};

/// The mass frame of a shape the state rule accepts (check_shape). A mesh
/// or a height field has no mass; its frame is the centre of its bounds
/// (so its bounds are symmetric about the body's position and the
/// broadphase bounds it like a box), axes unturned.
inline MassFrame mass_frame(const Shape& shape, const GeometryStore& store) {
  switch (shape.type) {
    case ShapeType::kHull: {
      const HullFrame& f = store.hull(shape.geometry)->frame;
      return {f.center, f.rotation, false};
    }
    case ShapeType::kMesh: {
      const Aabb& b = store.mesh(shape.geometry)->bounds;
      return {(b.lower + b.upper) * 0.5f, Quat{}, false};
    }
    case ShapeType::kHeightField: {
      const Aabb& b = store.height_field(shape.geometry)->bounds;
      return {(b.lower + b.upper) * 0.5f, Quat{}, false};
    }
    case ShapeType::kCompound: {
      const HullFrame& f = store.compound(shape.geometry)->frame;
      return {f.center, f.rotation, false};
    }
    case ShapeType::kSphere:
    case ShapeType::kBox:
    case ShapeType::kCapsule:
      break;
  }
  return {};
}

/// The mass-frame pose of a body whose authored frame is at `position`,
/// `rotation`.
inline void authored_to_mass(const MassFrame& f, Vec3 position, Quat rotation, Vec3& mass_position,
                             Quat& mass_rotation) {
  if (f.identity) {
    mass_position = position;
    mass_rotation = rotation;
    return;
  }
  mass_position = position + rotate(rotation, f.center);
  mass_rotation = normalize(rotation * f.rotation);
}

/// The authored pose of a body whose mass frame is at `mass_position`,
/// `mass_rotation`.
inline void mass_to_authored(const MassFrame& f, Vec3 mass_position, Quat mass_rotation,
                             Vec3& position, Quat& rotation) {
  if (f.identity) {
    position = mass_position;
    rotation = mass_rotation;
    return;
  }
  rotation = normalize(mass_rotation * conjugate(f.rotation));
  position = mass_position - rotate(rotation, f.center);
}

struct AuthoredPose {
  Vec3 position;
  Quat rotation;
};

/// Body slot i's pose in the frame its shape was authored in.
inline AuthoredPose authored_pose(const WorldState& state, const GeometryStore& store, uint32_t i) {
  const BodySim& sim = state.sims[i];
  AuthoredPose pose;
  mass_to_authored(mass_frame(state.infos[i].shape, store), sim.position, sim.rotation,
                   pose.position, pose.rotation);
  return pose;
}

}  // namespace rwd::sim::d3
