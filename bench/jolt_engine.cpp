// SPDX-License-Identifier: MIT
// How a BodySpec becomes a Jolt body (the table in docs/BENCHMARKS.md):
// - friction combines by geometric mean and restitution by maximum: Jolt's
//   own rules, the same as Rewind's; its restitution threshold
//   (mMinVelocityForRestitution) is 1 m/s, as Rewind's;
// - damping: Jolt scales velocity by (1 - c' dt) per step, so a decay rate
//   c (1/s) becomes c' = (1 - exp(-c dt)) / dt, exact at the step length;
// - sleeping: Jolt sleeps a body whose bounding-sphere points move slower
//   than mPointVelocitySleepThreshold for mTimeBeforeSleep; 0.05 m/s and
//   0.5 s mirror Rewind's |v| + extent |w| < 0.05 m/s for 0.5 s;
//   kinematic bodies never sleep (as in the Bullet adapter);
// - mass: density times the volume of the shape, inertia Jolt's own
//   (EOverrideMassProperties::CalculateInertia scales it to that mass);
// - shapes keep Jolt's default convex radius (0.05 m, inside a box's half
//   extents and a hull's faces, so sizes are exact; half the smallest half
//   extent for boxes thinner than 20 cm);
// - a hull is a ConvexHullShape of the points as given and a compound a
//   StaticCompoundShape of its children as placed: Jolt turns a body about
//   its centre of mass and reports the pose of the shape's own frame, which
//   is what Rewind reports, so no frame change is needed;
// - a mesh is a MeshShape over the same vertices and indices, a height
//   field a HeightFieldShape over the same samples: Jolt's field is square,
//   so a rows x cols field is padded with holes (cNoCollisionValue); it keeps
//   Jolt's default 8-bit sample compression per 2 x 2 block;
// - `continuous` bodies get EMotionQuality::LinearCast;
// - rolling resistance has no Jolt counterpart and is left out.
// Everything else is Jolt's default: 10 velocity and 2 position iterations,
// warm starting, speculative contacts (2 cm), Baumgarte 0.2, penetration
// slop 2 cm, no gyroscopic force, a 500 m/s and 47 rad/s velocity clamp.
//
// One thread: JobSystemSingleThreaded runs every job inline on the caller,
// so nothing waits on a barrier or a worker; a thread pool with no workers
// would run the same jobs on the same thread, through its queue.
#include "jolt_engine.h"

// Jolt.h (through jolt_setup.h) first: it sets up the configuration the
// other Jolt headers rely on.
#include "jolt_setup.h"

#include <Jolt/Core/JobSystemSingleThreaded.h>
#include <Jolt/Core/TempAllocator.h>
#include <Jolt/Physics/Body/BodyCreationSettings.h>
#include <Jolt/Physics/Collision/Shape/BoxShape.h>
#include <Jolt/Physics/Collision/Shape/CapsuleShape.h>
#include <Jolt/Physics/Collision/Shape/ConvexHullShape.h>
#include <Jolt/Physics/Collision/Shape/HeightFieldShape.h>
#include <Jolt/Physics/Collision/Shape/MeshShape.h>
#include <Jolt/Physics/Collision/Shape/SphereShape.h>
#include <Jolt/Physics/Collision/Shape/StaticCompoundShape.h>
#include <Jolt/Physics/PhysicsSettings.h>
#include <Jolt/Physics/PhysicsSystem.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace rwd::bench {

using jolt_setup::BroadPhaseLayers;
using jolt_setup::kMovingLayer;
using jolt_setup::kStaticLayer;
using jolt_setup::ObjectPairs;
using jolt_setup::ObjectVsBroadPhase;
using scenes::BodyHandle;
using scenes::BodySpec;
using scenes::Quat;
using scenes::Vec3;

namespace {

JPH::Vec3 jv(Vec3 v) {
  return {v.x, v.y, v.z};
}
Vec3 rw(JPH::Vec3Arg v) {
  return {v.GetX(), v.GetY(), v.GetZ()};
}
JPH::Quat jq(Quat q) {
  const Quat n = sim::normalize(q);
  return {n.x, n.y, n.z, n.w};
}

// Jolt's convex radius, no larger than a thin box can carry.
float box_radius(Vec3 half) {
  const float smallest = std::min(half.x, std::min(half.y, half.z));
  return std::min(JPH::cDefaultConvexRadius, 0.5f * smallest);
}

JPH::RefConst<JPH::Shape> box_shape(Vec3 half) {
  return new JPH::BoxShape(jv(half), box_radius(half));
}

}  // namespace

// A registered geometry: hulls and compounds for any body, meshes and
// height fields for static ones; one numbering, as in Rewind.
struct JoltGeometry {
  JPH::RefConst<JPH::Shape> shape;
  bool surface = false;   // mesh or height field
  bool compound = false;  // may not be a child of another compound
};

struct JoltEngine::World {
  explicit World(JPH::uint temp_bytes) : temp(temp_bytes) {}

  BroadPhaseLayers layers;
  ObjectVsBroadPhase object_vs_broad_phase;
  ObjectPairs object_pairs;
  JPH::PhysicsSystem system;
  JPH::TempAllocatorImplWithMallocFallback temp;
  JPH::JobSystemSingleThreaded jobs{JPH::cMaxPhysicsJobs};
  std::vector<JoltGeometry> geometry;
  std::vector<JPH::BodyID> bodies;
  std::vector<JPH::BodyID> dynamic_bodies;
  scenes::WorldSpec spec;
  float step_s = 1.0f / 60.0f;
  bool optimized = false;
  bool warned = false;

  JPH::BodyInterface& api() { return system.GetBodyInterfaceNoLock(); }
  const JPH::BodyInterface& api() const { return system.GetBodyInterfaceNoLock(); }

  ~World() {
    JPH::BodyInterface& b = api();
    for (const JPH::BodyID& id : bodies) {
      b.RemoveBody(id);
      b.DestroyBody(id);
    }
  }
};

JoltEngine::JoltEngine(const JoltSettings& settings) : settings_(settings) {
  jolt_setup::init_once();
}
JoltEngine::~JoltEngine() = default;

std::string JoltEngine::settings() const {
  std::ostringstream out;
  out << "velocity_iterations=" << settings_.velocity_iterations
      << " position_iterations=" << settings_.position_iterations
      << " collision_steps=" << settings_.collision_steps;
  if (!settings_.sleep) out << " sleep=off";
  return out.str();
}

void JoltEngine::reset(const scenes::WorldSpec& world, uint32_t body_capacity) {
  // Room for every pair and contact a dense pile makes, 16 a body (Jolt
  // drops contacts beyond these, and says so from Update). Sized to the
  // scene: Jolt takes a buffer for every possible contact from its temp
  // allocator each step, and one larger than the allocator's block goes to
  // malloc, mmap and munmap every step. 1 KiB a contact covers the contact
  // buffer and the step's other scratch data.
  const JPH::uint bodies = std::max<JPH::uint>(body_capacity, 16);
  const JPH::uint pairs = std::max<JPH::uint>(1024, 16 * bodies);
  world_.reset();
  world_ = std::make_unique<World>(4u * 1024u * 1024u + 1024u * pairs);
  world_->spec = world;
  world_->step_s = world.tick_seconds / static_cast<float>(settings_.collision_steps);
  world_->system.Init(bodies, 0, pairs, pairs, world_->layers, world_->object_vs_broad_phase,
                      world_->object_pairs);
  world_->bodies.reserve(body_capacity);
  JPH::PhysicsSettings s = world_->system.GetPhysicsSettings();
  s.mNumVelocitySteps = static_cast<JPH::uint>(settings_.velocity_iterations);
  s.mNumPositionSteps = static_cast<JPH::uint>(settings_.position_iterations);
  s.mAllowSleeping = settings_.sleep;
  s.mPointVelocitySleepThreshold = 0.05f;
  s.mTimeBeforeSleep = 0.5f;
  world_->system.SetPhysicsSettings(s);
  world_->system.SetGravity(jv(world.gravity));
}

static bool add_geometry(std::vector<JoltGeometry>& geometry, JPH::ShapeSettings::ShapeResult r,
                         bool surface, bool compound, sim::GeometryId& out, std::string& error) {
  if (r.HasError()) {
    error = r.GetError().c_str();
    return false;
  }
  out = sim::GeometryId{static_cast<uint32_t>(geometry.size())};
  geometry.push_back({r.Get(), surface, compound});
  return true;
}

bool JoltEngine::add_hull(std::span<const Vec3> points, sim::GeometryId& out, std::string& error) {
  JPH::Array<JPH::Vec3> corners;
  for (const Vec3& p : points) corners.push_back(jv(p));
  JPH::ConvexHullShapeSettings hull(corners);
  hull.SetEmbedded();  // on the stack: no reference may delete it
  return add_geometry(world_->geometry, hull.Create(), false, false, out, error);
}

bool JoltEngine::add_compound(std::span<const sim::CompoundChild> children, sim::GeometryId& out,
                              std::string& error) {
  JPH::StaticCompoundShapeSettings compound;
  compound.SetEmbedded();
  for (const sim::CompoundChild& c : children) {
    JPH::RefConst<JPH::Shape> child;
    const sim::Shape& s = c.shape;
    if (s.type == sim::ShapeType::kSphere) {
      child = new JPH::SphereShape(s.radius);
    } else if (s.type == sim::ShapeType::kCapsule) {
      child = new JPH::CapsuleShape(s.half_height, s.radius);
    } else if (s.type == sim::ShapeType::kBox) {
      child = box_shape(s.half_extents);
    } else if (s.type == sim::ShapeType::kHull && s.geometry < world_->geometry.size() &&
               !world_->geometry[s.geometry].surface && !world_->geometry[s.geometry].compound) {
      child = world_->geometry[s.geometry].shape;
    } else {
      error = "compound child is not a sphere, box, capsule or registered hull";
      return false;
    }
    compound.AddShape(jv(c.position), jq(c.rotation), child);
  }
  return add_geometry(world_->geometry, compound.Create(), false, true, out, error);
}

bool JoltEngine::add_mesh(std::span<const Vec3> vertices, std::span<const uint32_t> indices,
                          sim::GeometryId& out, std::string& error) {
  if (vertices.size() < 3 || indices.empty() || indices.size() % 3 != 0) {
    error = "a mesh needs 3 or more vertices and whole triangles";
    return false;
  }
  JPH::VertexList points;
  for (const Vec3& v : vertices) points.push_back({v.x, v.y, v.z});
  JPH::IndexedTriangleList triangles;
  for (size_t i = 0; i < indices.size(); i += 3) {
    if (std::max(indices[i], std::max(indices[i + 1], indices[i + 2])) >= vertices.size()) {
      error = "mesh index out of range";
      return false;
    }
    triangles.push_back(JPH::IndexedTriangle(indices[i], indices[i + 1], indices[i + 2], 0));
  }
  JPH::MeshShapeSettings mesh(std::move(points), std::move(triangles));
  mesh.SetEmbedded();
  return add_geometry(world_->geometry, mesh.Create(), true, false, out, error);
}

bool JoltEngine::add_height_field(uint32_t rows, uint32_t cols, Vec3 scale,
                                  std::span<const float> heights, sim::GeometryId& out,
                                  std::string& error) {
  if (rows < 2 || cols < 2 || heights.size() != static_cast<size_t>(rows) * cols) {
    error = "a height field needs 2 x 2 samples or more, one height each";
    return false;
  }
  // Jolt's sample (x, y) lies at scale * (x, height, y): x is Rewind's
  // column, y its row.
  const uint32_t n = std::max(rows, cols);
  std::vector<float> square(static_cast<size_t>(n) * n,
                            JPH::HeightFieldShapeConstants::cNoCollisionValue);
  for (uint32_t r = 0; r < rows; ++r) {
    for (uint32_t c = 0; c < cols; ++c) {
      square[static_cast<size_t>(r) * n + c] = heights[static_cast<size_t>(r) * cols + c];
    }
  }
  JPH::HeightFieldShapeSettings field(square.data(), JPH::Vec3::sZero(), jv(scale), n);
  field.SetEmbedded();
  return add_geometry(world_->geometry, field.Create(), true, false, out, error);
}

bool JoltEngine::add_body(const BodySpec& spec, BodyHandle& out, std::string& error) {
  JPH::RefConst<JPH::Shape> shape;
  const sim::Shape& s = spec.shape;
  switch (s.type) {
    case sim::ShapeType::kSphere:
      shape = new JPH::SphereShape(s.radius);
      break;
    case sim::ShapeType::kCapsule:
      // Both capsules stand along local y; Jolt's half height is that of
      // its cylinder, Rewind's half the distance between the cap centres.
      shape = new JPH::CapsuleShape(s.half_height, s.radius);
      break;
    case sim::ShapeType::kBox:
      shape = box_shape(s.half_extents);
      break;
    case sim::ShapeType::kHull:
    case sim::ShapeType::kCompound:
    case sim::ShapeType::kMesh:
    case sim::ShapeType::kHeightField: {
      const bool surface =
          s.type == sim::ShapeType::kMesh || s.type == sim::ShapeType::kHeightField;
      if (s.geometry >= world_->geometry.size() ||
          world_->geometry[s.geometry].surface != surface ||
          (surface && spec.kind == sim::BodyKind::kDynamic)) {
        error = "unknown geometry, or a dynamic mesh or height field";
        return false;
      }
      shape = world_->geometry[s.geometry].shape;
      break;
    }
    default:
      error = "shape type this adapter does not map";
      return false;
  }
  const bool is_static = spec.kind == sim::BodyKind::kStatic;
  const bool dynamic = spec.kind == sim::BodyKind::kDynamic;
  JPH::BodyCreationSettings b(shape, jv(spec.position), jq(spec.rotation),
                              is_static ? JPH::EMotionType::Static
                              : dynamic ? JPH::EMotionType::Dynamic
                                        : JPH::EMotionType::Kinematic,
                              is_static ? kStaticLayer : kMovingLayer);
  b.mFriction = spec.friction;
  b.mRestitution = spec.restitution;
  // Jolt's damping multiplies by (1 - c' dt) each step; this c' decays by
  // exp(-c dt) per step, as the scene's rate asks.
  const float dt = world_->step_s;
  b.mLinearDamping = (1.0f - std::exp(-spec.linear_damping * dt)) / dt;
  b.mAngularDamping = (1.0f - std::exp(-spec.angular_damping * dt)) / dt;
  b.mAllowSleeping = dynamic && settings_.sleep;
  if (spec.continuous) b.mMotionQuality = JPH::EMotionQuality::LinearCast;
  if (dynamic) {
    b.mOverrideMassProperties = JPH::EOverrideMassProperties::CalculateInertia;
    b.mMassPropertiesOverride.mMass = spec.density * shape->GetVolume();
  }
  if (!is_static) {
    b.mLinearVelocity = jv(spec.linear_velocity);
    b.mAngularVelocity = jv(spec.angular_velocity);
  }
  JPH::BodyInterface& api = world_->api();
  const JPH::BodyID id = api.CreateAndAddBody(
      b, is_static ? JPH::EActivation::DontActivate : JPH::EActivation::Activate);
  if (id.IsInvalid()) {
    error = "Jolt is out of bodies (more than the scene's body_capacity)";
    return false;
  }
  out = static_cast<BodyHandle>(world_->bodies.size());
  world_->bodies.push_back(id);
  if (dynamic) world_->dynamic_bodies.push_back(id);
  return true;
}

void JoltEngine::step() {
  // Jolt's advice after adding bodies in bulk: rebuild the broadphase tree
  // once before the first step (bodies added later go in incrementally).
  if (!world_->optimized) {
    world_->system.OptimizeBroadPhase();
    world_->optimized = true;
  }
  const JPH::EPhysicsUpdateError e = world_->system.Update(
      world_->spec.tick_seconds, settings_.collision_steps, &world_->temp, &world_->jobs);
  if (e != JPH::EPhysicsUpdateError::None && !world_->warned) {
    std::fprintf(stderr, "jolt: PhysicsSystem::Update reported error flags %u (caches full)\n",
                 static_cast<unsigned>(e));
    world_->warned = true;
  }
}

Vec3 JoltEngine::position(BodyHandle body) const {
  return rw(world_->api().GetPosition(world_->bodies[body]));
}
Quat JoltEngine::rotation(BodyHandle body) const {
  const JPH::Quat q = world_->api().GetRotation(world_->bodies[body]);
  return {q.GetX(), q.GetY(), q.GetZ(), q.GetW()};
}
Vec3 JoltEngine::linear_velocity(BodyHandle body) const {
  return rw(world_->api().GetLinearVelocity(world_->bodies[body]));
}
Vec3 JoltEngine::angular_velocity(BodyHandle body) const {
  return rw(world_->api().GetAngularVelocity(world_->bodies[body]));
}

bool JoltEngine::enabled(BodyHandle body) const {
  // Jolt has no world bounds; a body outside the scene's region is lost.
  const Vec3 p = position(body);
  const Vec3 lo = world_->spec.bounds_lower;
  const Vec3 hi = world_->spec.bounds_upper;
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && p.x >= lo.x &&
         p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
}

void JoltEngine::apply_impulse(BodyHandle body, Vec3 impulse_ns, Vec3 world_point) {
  // AddImpulse wakes the body.
  world_->api().AddImpulse(world_->bodies[body], jv(impulse_ns), jv(world_point));
}

void JoltEngine::set_velocity(BodyHandle body, Vec3 linear_mps, Vec3 angular_radps) {
  JPH::BodyInterface& api = world_->api();
  const JPH::BodyID id = world_->bodies[body];
  // Jolt wakes the body only for a non-zero velocity; the interface wakes
  // it always.
  api.ActivateBody(id);
  api.SetLinearAndAngularVelocity(id, jv(linear_mps), jv(angular_radps));
}

uint32_t JoltEngine::awake_count() const {
  uint32_t awake = 0;
  const JPH::BodyInterface& api = world_->api();
  for (const JPH::BodyID& id : world_->dynamic_bodies) {
    if (api.IsActive(id)) ++awake;
  }
  return awake;
}

}  // namespace rwd::bench
