// SPDX-License-Identifier: MIT
// How a BodySpec becomes a Bullet body (the table in docs/BENCHMARKS.md):
// - friction combines by geometric mean and restitution by maximum, as in
//   Rewind, through a contact-added callback (Bullet's own rules multiply);
// - damping: Bullet scales velocity by (1 - d)^dt per step, so a decay rate
//   c (1/s) becomes d = 1 - exp(-c);
// - restitution threshold 1 m/s (Rewind's restitution_threshold_mps);
// - sleeping: Bullet sleeps a body when |v| < lin and |w| < ang for
//   gDeactivationTime; lin = 0.05 m/s, ang = 0.05 m/s over the body's extent
//   and 0.5 s mirror Rewind's |v| + extent |w| < 0.05 m/s for 0.5 s;
// - shapes keep Bullet's default collision margin (0.04 m, inside a box's
//   half extents; a sphere's margin is its radius), so sizes are exact;
//   boxes thinner than 8 cm get half their smallest half extent instead;
// - `continuous` bodies get Bullet's swept-sphere CCD;
// - a hull becomes a btConvexHullShape of its corners moved into its mass
//   frame (centre of mass, principal axes: Bullet turns a body about its
//   origin), with the exact principal inertia rather than Bullet's
//   bounding-box estimate; positions are reported back in the frame the
//   points were given in, as Rewind reports them. Rewind's hull builder
//   supplies the corners, mass frame and inertia, so both engines simulate
//   the same solid;
// - a mesh becomes a btBvhTriangleMeshShape (quantized AABB tree) over the
//   same vertices and indices, a height field a btHeightfieldTerrainShape
//   over the same samples (Bullet centres it on its bounds, so its body sits
//   at the centre of the field's bounds, as Rewind's does); both keep
//   Bullet's default margin and no internal-edge correction (Bullet's
//   default).
// Everything else is Bullet's default: split impulse, erp 0.2, warm starting,
// SIMD solver, dynamic AABB tree broadphase, gyroscopic term on.
#include "bullet_engine.h"

#include "rewind/sim/geometry.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace rwd::bench {

using scenes::BodyHandle;
using scenes::BodySpec;
using scenes::Quat;
using scenes::Vec3;

namespace {

btVector3 bt(Vec3 v) {
  return {v.x, v.y, v.z};
}
Vec3 rw(const btVector3& v) {
  return {v.x(), v.y(), v.z()};
}

// Per-body surface values, kept where the callback can reach them.
struct Surface {
  float friction = 0.0f;
  float restitution = 0.0f;
  float rolling = 0.0f;  // Bullet's rolling friction (a length)
};

bool combine_like_rewind(btManifoldPoint& cp, const btCollisionObjectWrapper* a, int, int,
                         const btCollisionObjectWrapper* b, int, int) {
  const auto* sa = static_cast<const Surface*>(a->getCollisionObject()->getUserPointer());
  const auto* sb = static_cast<const Surface*>(b->getCollisionObject()->getUserPointer());
  if (sa == nullptr || sb == nullptr) return false;
  cp.m_combinedFriction = std::sqrt(sa->friction * sb->friction);
  cp.m_combinedRestitution = std::max(sa->restitution, sb->restitution);
  cp.m_combinedRollingFriction = std::max(sa->rolling, sb->rolling);
  return true;
}

}  // namespace

// A registered hull as Bullet gets it.
struct BulletChild {
  sim::Shape shape;  // sphere, box, capsule, or hull (geometry: index in hulls)
  Vec3 position;     // in the compound's mass frame
  Quat rotation;
};

// A registered hull, or a compound (children non-empty, corners empty).
struct BulletHull {
  std::vector<Vec3> authored;      // the corners as given (hulls)
  std::vector<btVector3> corners;  // in the mass frame
  float volume = 0.0f;
  Vec3 unit_inertia;  // principal moments per kg
  float extent = 0.0f;
  float smallest = 0.0f;  // smallest half size of the mass-frame bounds
  Vec3 center;            // mass frame in the authored frame
  Quat rotation;
  std::vector<BulletChild> children;
};

// A hull's corners as Bullet's convex hull, its margin no larger than a thin
// hull can carry (Bullet's margin rounds a hull outward).
static std::unique_ptr<btCollisionShape> convex_hull_shape(const BulletHull& h) {
  auto hull =
      std::make_unique<btConvexHullShape>(h.corners[0].m_floats, static_cast<int>(h.corners.size()),
                                          static_cast<int>(sizeof(btVector3)));
  if (hull->getMargin() > 0.5f * h.smallest) hull->setMargin(0.5f * h.smallest);
  return hull;
}

// A registered mesh or height field: the data Bullet's shapes point into
// (kept alive and unmoved for the world's lifetime) and the shape itself,
// shared by the bodies of it.
struct BulletSurface {
  std::vector<btVector3> vertices;
  std::vector<int> indices;
  std::vector<float> heights;
  std::unique_ptr<btTriangleIndexVertexArray> arrays;
  std::unique_ptr<btCollisionShape> shape;
  Vec3 offset;  // where the shape's origin sits from the body's position
};

struct BulletEngine::World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<Surface> surfaces;  // reserved up front: bodies point into it
  std::vector<BulletHull> hulls;
  // Geometry ids: hulls and surfaces share one numbering, as in Rewind.
  std::vector<int> geometry_hull;     // per id: index in hulls, or -1
  std::vector<int> geometry_surface;  // per id: index in surfaces, or -1
  std::vector<std::unique_ptr<BulletSurface>> surfaces_geometry;
  std::vector<int> body_hull;  // per body: its hull, or -1
  scenes::WorldSpec spec;
  float substep_s = 1.0f / 60.0f;

  ~World() {
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
};

BulletEngine::BulletEngine(const BulletSettings& settings) : settings_(settings) {}
BulletEngine::~BulletEngine() = default;

std::string BulletEngine::settings() const {
  std::ostringstream out;
  out << "iterations=" << settings_.iterations << " substeps=" << settings_.substeps;
  if (!settings_.sleep) out << " sleep=off";
  return out.str();
}

void BulletEngine::reset(const scenes::WorldSpec& world, uint32_t body_capacity) {
  world_.reset();
  world_ = std::make_unique<World>();
  world_->spec = world;
  world_->surfaces.reserve(body_capacity);
  world_->bodies.reserve(body_capacity);
  world_->substep_s = world.tick_seconds / static_cast<float>(settings_.substeps);
  world_->world.setGravity(bt(world.gravity));
  btContactSolverInfo& info = world_->world.getSolverInfo();
  info.m_numIterations = settings_.iterations;
  info.m_restitutionVelocityThreshold = 1.0f;
  gContactAddedCallback = combine_like_rewind;
  gDeactivationTime = 0.5f;
}

bool BulletEngine::add_hull(std::span<const Vec3> points, sim::GeometryId& out,
                            std::string& error) {
  sim::GeometryStore store;
  auto id = store.add_hull(points);
  if (!id.ok()) {
    error = id.status().message();
    return false;
  }
  const auto info = store.hull_info(*id);
  std::vector<Vec3> corners;
  store.hull_vertices(*id, corners);
  BulletHull h;
  h.authored.assign(points.begin(), points.end());
  h.volume = info->volume;
  h.unit_inertia = info->unit_inertia;
  h.center = info->center_of_mass;
  h.rotation = info->principal_axes;
  Vec3 lo{1e30f, 1e30f, 1e30f};
  Vec3 hi{-1e30f, -1e30f, -1e30f};
  for (const Vec3& c : corners) {
    const Vec3 m = sim::inv_rotate(h.rotation, c - h.center);
    h.corners.push_back(bt(m));
    h.extent = std::max(h.extent, sim::length(m));
    lo = sim::min(lo, m);
    hi = sim::max(hi, m);
  }
  const Vec3 half = (hi - lo) * 0.5f;
  h.smallest = std::min(half.x, std::min(half.y, half.z));
  world_->hulls.push_back(std::move(h));
  out = sim::GeometryId{static_cast<uint32_t>(world_->geometry_hull.size())};
  world_->geometry_hull.push_back(static_cast<int>(world_->hulls.size() - 1));
  world_->geometry_surface.push_back(-1);
  return true;
}

bool BulletEngine::add_compound(std::span<const sim::CompoundChild> children, sim::GeometryId& out,
                                std::string& error) {
  // Rewind's builder gives the mass frame; hull children are registered in
  // its store again from the corners they were given.
  sim::GeometryStore store;
  std::vector<sim::CompoundChild> local(children.begin(), children.end());
  std::vector<int> child_hull(children.size(), -1);
  for (size_t i = 0; i < local.size(); ++i) {
    if (local[i].shape.type != sim::ShapeType::kHull) continue;
    const uint32_t g = local[i].shape.geometry;
    if (g >= world_->geometry_hull.size() || world_->geometry_hull[g] < 0 ||
        !world_->hulls[static_cast<size_t>(world_->geometry_hull[g])].children.empty()) {
      error = "compound child refers to an unknown hull";
      return false;
    }
    child_hull[i] = world_->geometry_hull[g];
    auto id = store.add_hull(world_->hulls[static_cast<size_t>(child_hull[i])].authored);
    if (!id.ok()) {
      error = id.status().message();
      return false;
    }
    local[i].shape.geometry = id->value;
  }
  auto id = store.add_compound(local);
  if (!id.ok()) {
    error = id.status().message();
    return false;
  }
  const auto info = store.compound_info(*id);
  BulletHull h;
  h.volume = info->volume;
  h.unit_inertia = info->unit_inertia;
  h.center = info->center_of_mass;
  h.rotation = info->principal_axes;
  h.smallest = 1e30f;
  for (size_t i = 0; i < children.size(); ++i) {
    Vec3 p = children[i].position;
    Quat q = sim::normalize(children[i].rotation);
    float reach = 0.0f;
    const sim::Shape& s = children[i].shape;
    if (child_hull[i] >= 0) {
      const BulletHull& hull = world_->hulls[static_cast<size_t>(child_hull[i])];
      p = p + sim::rotate(q, hull.center);
      q = q * hull.rotation;
      reach = hull.extent;
      h.smallest = std::min(h.smallest, hull.smallest);
    } else {
      reach =
          s.type == sim::ShapeType::kBox ? sim::length(s.half_extents) : s.radius + s.half_height;
      h.smallest = std::min(
          h.smallest, s.type == sim::ShapeType::kBox
                          ? std::min(s.half_extents.x, std::min(s.half_extents.y, s.half_extents.z))
                          : s.radius);
    }
    BulletChild c;
    c.shape = s;
    if (child_hull[i] >= 0) c.shape.geometry = static_cast<uint32_t>(child_hull[i]);
    c.position = sim::inv_rotate(h.rotation, p - h.center);
    c.rotation = sim::conjugate(h.rotation) * q;
    h.extent = std::max(h.extent, sim::length(c.position) + reach);
    h.children.push_back(c);
  }
  world_->hulls.push_back(std::move(h));
  out = sim::GeometryId{static_cast<uint32_t>(world_->geometry_hull.size())};
  world_->geometry_hull.push_back(static_cast<int>(world_->hulls.size() - 1));
  world_->geometry_surface.push_back(-1);
  return true;
}

bool BulletEngine::add_mesh(std::span<const Vec3> vertices, std::span<const uint32_t> indices,
                            sim::GeometryId& out, std::string& error) {
  if (vertices.size() < 3 || indices.empty() || indices.size() % 3 != 0) {
    error = "a mesh needs 3 or more vertices and whole triangles";
    return false;
  }
  auto s = std::make_unique<BulletSurface>();
  for (const Vec3& v : vertices) s->vertices.push_back(bt(v));
  for (uint32_t i : indices) {
    if (i >= vertices.size()) {
      error = "mesh index out of range";
      return false;
    }
    s->indices.push_back(static_cast<int>(i));
  }
  s->arrays = std::make_unique<btTriangleIndexVertexArray>(
      static_cast<int>(s->indices.size() / 3), s->indices.data(), 3 * static_cast<int>(sizeof(int)),
      static_cast<int>(s->vertices.size()), s->vertices[0].m_floats,
      static_cast<int>(sizeof(btVector3)));
  s->shape = std::make_unique<btBvhTriangleMeshShape>(s->arrays.get(), true);
  world_->surfaces_geometry.push_back(std::move(s));
  out = sim::GeometryId{static_cast<uint32_t>(world_->geometry_hull.size())};
  world_->geometry_hull.push_back(-1);
  world_->geometry_surface.push_back(static_cast<int>(world_->surfaces_geometry.size() - 1));
  return true;
}

bool BulletEngine::add_height_field(uint32_t rows, uint32_t cols, Vec3 scale,
                                    std::span<const float> heights, sim::GeometryId& out,
                                    std::string& error) {
  if (rows < 2 || cols < 2 || heights.size() != static_cast<size_t>(rows) * cols) {
    error = "a height field needs 2 x 2 samples or more, one height each";
    return false;
  }
  auto s = std::make_unique<BulletSurface>();
  s->heights.assign(heights.begin(), heights.end());
  float lo = s->heights[0];
  float hi = s->heights[0];
  for (float h : s->heights) {
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  auto field = std::make_unique<btHeightfieldTerrainShape>(
      static_cast<int>(cols), static_cast<int>(rows), s->heights.data(), 1.0f, lo, hi, 1, PHY_FLOAT,
      false);
  field->setLocalScaling(btVector3(scale.x, scale.y, scale.z));
  s->shape = std::move(field);
  // Bullet puts the field's origin at the centre of its bounds.
  s->offset = {0.5f * static_cast<float>(cols - 1) * scale.x, 0.5f * (lo + hi) * scale.y,
               0.5f * static_cast<float>(rows - 1) * scale.z};
  world_->surfaces_geometry.push_back(std::move(s));
  out = sim::GeometryId{static_cast<uint32_t>(world_->geometry_hull.size())};
  world_->geometry_hull.push_back(-1);
  world_->geometry_surface.push_back(static_cast<int>(world_->surfaces_geometry.size() - 1));
  return true;
}

bool BulletEngine::add_body(const BodySpec& spec, BodyHandle& out, std::string& error) {
  if (world_->surfaces.size() == world_->surfaces.capacity()) {
    error = "more bodies than the scene's body_capacity";
    return false;
  }
  std::unique_ptr<btCollisionShape> shape;
  const BulletSurface* surface = nullptr;  // shared, owned by the world
  int hull_index = -1;
  float volume = 0.0f;
  float extent = 0.0f;
  float smallest = 0.0f;
  if (spec.shape.type == sim::ShapeType::kSphere) {
    const float r = spec.shape.radius;
    shape = std::make_unique<btSphereShape>(r);
    volume = 4.0f / 3.0f * 3.14159265f * r * r * r;
    extent = r;
    smallest = r;
  } else if (spec.shape.type == sim::ShapeType::kCapsule) {
    // Bullet's capsule stands along its local y like Rewind's; its height
    // is the distance between the cap centres.
    const float r = spec.shape.radius;
    const float h = spec.shape.half_height;
    shape = std::make_unique<btCapsuleShape>(r, 2.0f * h);
    volume = 3.14159265f * r * r * 2.0f * h + 4.0f / 3.0f * 3.14159265f * r * r * r;
    extent = h + r;
    smallest = r;
  } else if (spec.shape.type == sim::ShapeType::kMesh ||
             spec.shape.type == sim::ShapeType::kHeightField) {
    if (spec.shape.geometry >= world_->geometry_surface.size() ||
        world_->geometry_surface[spec.shape.geometry] < 0 || spec.kind == sim::BodyKind::kDynamic) {
      error = "unknown surface, or a dynamic one";
      return false;
    }
    surface =
        world_
            ->surfaces_geometry[static_cast<size_t>(world_->geometry_surface[spec.shape.geometry])]
            .get();
    extent = 1.0f;
    smallest = 1.0f;
  } else if (spec.shape.type == sim::ShapeType::kHull ||
             spec.shape.type == sim::ShapeType::kCompound) {
    if (spec.shape.geometry >= world_->geometry_hull.size() ||
        world_->geometry_hull[spec.shape.geometry] < 0) {
      error = "unknown hull or compound";
      return false;
    }
    const size_t hull_at = static_cast<size_t>(world_->geometry_hull[spec.shape.geometry]);
    const BulletHull& h = world_->hulls[hull_at];
    if (h.children.empty()) {
      shape = convex_hull_shape(h);
    } else {
      // The children in the compound's mass frame, owned with the world's
      // shapes (the compound only points at them).
      auto compound = std::make_unique<btCompoundShape>();
      for (const BulletChild& c : h.children) {
        std::unique_ptr<btCollisionShape> child;
        if (c.shape.type == sim::ShapeType::kSphere) {
          child = std::make_unique<btSphereShape>(c.shape.radius);
        } else if (c.shape.type == sim::ShapeType::kCapsule) {
          child = std::make_unique<btCapsuleShape>(c.shape.radius, 2.0f * c.shape.half_height);
        } else if (c.shape.type == sim::ShapeType::kBox) {
          auto box = std::make_unique<btBoxShape>(bt(c.shape.half_extents));
          const Vec3 e = c.shape.half_extents;
          const float thin = std::min(e.x, std::min(e.y, e.z));
          if (box->getMargin() > 0.5f * thin) box->setMargin(0.5f * thin);
          child = std::move(box);
        } else {
          child = convex_hull_shape(world_->hulls[c.shape.geometry]);
        }
        btTransform at;
        at.setOrigin(bt(c.position));
        at.setRotation(btQuaternion(c.rotation.x, c.rotation.y, c.rotation.z, c.rotation.w));
        compound->addChildShape(at, child.get());
        world_->shapes.push_back(std::move(child));
      }
      shape = std::move(compound);
    }
    volume = h.volume;
    extent = h.extent;
    smallest = h.smallest;
    hull_index = static_cast<int>(hull_at);
  } else if (spec.shape.type == sim::ShapeType::kBox) {
    const Vec3 h = spec.shape.half_extents;
    smallest = std::min(h.x, std::min(h.y, h.z));
    auto box = std::make_unique<btBoxShape>(bt(h));
    // The margin lies inside the half extents; thin boxes (cards, walls)
    // need a smaller one than the default 0.04 m or their core inverts.
    // setMargin keeps the outer size.
    if (box->getMargin() > 0.5f * smallest) box->setMargin(0.5f * smallest);
    shape = std::move(box);
    volume = 8.0f * h.x * h.y * h.z;
    extent = std::sqrt(sim::length_squared(h));
  } else {
    error = "shape type this adapter does not map";
    return false;
  }
  const bool dynamic = spec.kind == sim::BodyKind::kDynamic;
  const float mass = dynamic ? spec.density * volume : 0.0f;
  btVector3 inertia(0.0f, 0.0f, 0.0f);
  btCollisionShape* collision_shape = surface != nullptr ? surface->shape.get() : shape.get();
  if (dynamic) collision_shape->calculateLocalInertia(mass, inertia);
  Vec3 position = spec.position;
  Quat rotation = spec.rotation;
  if (hull_index >= 0) {
    const BulletHull& h = world_->hulls[static_cast<size_t>(hull_index)];
    if (dynamic) inertia = bt(h.unit_inertia * mass);
    position = spec.position + sim::rotate(spec.rotation, h.center);
    rotation = spec.rotation * h.rotation;
  }
  if (surface != nullptr) position = spec.position + sim::rotate(spec.rotation, surface->offset);
  btTransform pose;
  pose.setOrigin(bt(position));
  pose.setRotation(btQuaternion(rotation.x, rotation.y, rotation.z, rotation.w));
  btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, collision_shape, inertia);
  ci.m_startWorldTransform = pose;
  ci.m_friction = spec.friction;
  ci.m_restitution = spec.restitution;
  // Bullet's rolling friction is an angular impulse per unit normal impulse
  // (a length): the coefficient times the body's smallest half size (a
  // ball's radius).
  ci.m_rollingFriction = spec.rolling_resistance * smallest;
  ci.m_linearDamping = 1.0f - std::exp(-spec.linear_damping);
  ci.m_angularDamping = 1.0f - std::exp(-spec.angular_damping);
  ci.m_linearSleepingThreshold = 0.05f;
  ci.m_angularSleepingThreshold = 0.05f / extent;
  auto body = std::make_unique<btRigidBody>(ci);
  world_->surfaces.push_back({spec.friction, spec.restitution, ci.m_rollingFriction});
  body->setUserPointer(&world_->surfaces.back());
  body->setCollisionFlags(body->getCollisionFlags() |
                          btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
  if (spec.kind == sim::BodyKind::kKinematic) {
    body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    body->setActivationState(DISABLE_DEACTIVATION);
  }
  if (dynamic && !settings_.sleep) body->setActivationState(DISABLE_DEACTIVATION);
  if (spec.kind != sim::BodyKind::kStatic) {
    body->setLinearVelocity(bt(spec.linear_velocity));
    body->setAngularVelocity(bt(spec.angular_velocity));
  }
  if (spec.continuous) {
    body->setCcdMotionThreshold(0.5f * smallest);
    body->setCcdSweptSphereRadius(0.8f * smallest);
  }
  world_->world.addRigidBody(body.get());
  out = static_cast<BodyHandle>(world_->bodies.size());
  world_->shapes.push_back(std::move(shape));
  world_->bodies.push_back(std::move(body));
  world_->body_hull.push_back(hull_index);
  return true;
}

void BulletEngine::step() {
  // One call per internal step with maxSubSteps = 0 (a variable step of
  // exactly h): Bullet's own fixed-step accumulator can drop or add a step
  // to float round-off.
  for (int i = 0; i < settings_.substeps; ++i) {
    world_->world.stepSimulation(world_->substep_s, 0);
  }
}

Quat BulletEngine::rotation(BodyHandle body) const {
  const btQuaternion q = world_->bodies[body]->getWorldTransform().getRotation();
  const Quat mass_rotation{q.x(), q.y(), q.z(), q.w()};
  const int hull = world_->body_hull[body];
  if (hull < 0) return mass_rotation;
  return mass_rotation * sim::conjugate(world_->hulls[static_cast<size_t>(hull)].rotation);
}
Vec3 BulletEngine::position(BodyHandle body) const {
  const Vec3 p = rw(world_->bodies[body]->getWorldTransform().getOrigin());
  const int hull = world_->body_hull[body];
  if (hull < 0) return p;
  return p - sim::rotate(rotation(body), world_->hulls[static_cast<size_t>(hull)].center);
}
Vec3 BulletEngine::linear_velocity(BodyHandle body) const {
  return rw(world_->bodies[body]->getLinearVelocity());
}
Vec3 BulletEngine::angular_velocity(BodyHandle body) const {
  return rw(world_->bodies[body]->getAngularVelocity());
}

bool BulletEngine::enabled(BodyHandle body) const {
  // Bullet has no world bounds; a body outside the scene's region is lost.
  const Vec3 p = position(body);
  const Vec3 lo = world_->spec.bounds_lower;
  const Vec3 hi = world_->spec.bounds_upper;
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && p.x >= lo.x &&
         p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
}

void BulletEngine::apply_impulse(BodyHandle body, Vec3 impulse_ns, Vec3 world_point) {
  btRigidBody& b = *world_->bodies[body];
  b.activate(true);
  b.applyImpulse(bt(impulse_ns), bt(world_point) - b.getCenterOfMassPosition());
}

void BulletEngine::set_velocity(BodyHandle body, Vec3 linear_mps, Vec3 angular_radps) {
  btRigidBody& b = *world_->bodies[body];
  b.activate(true);
  b.setLinearVelocity(bt(linear_mps));
  b.setAngularVelocity(bt(angular_radps));
}

uint32_t BulletEngine::awake_count() const {
  uint32_t awake = 0;
  for (const auto& b : world_->bodies) {
    if (!b->isStaticOrKinematicObject() && b->isActive()) ++awake;
  }
  return awake;
}

}  // namespace rwd::bench
