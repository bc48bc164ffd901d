// SPDX-License-Identifier: MIT
#pragma once
// The query benchmark's level: the 10,000 boxes built in both engines, the
// queries and sweeps drawn over it, and each engine's answer to one query
// (bench/query_bench.cpp times them and checks that the engines agree).
#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include "rewind/core/splitmix64.h"
#include "rewind/sim/world3d.h"

namespace rwd::bench::query_level {

using rwd::sim::BodyDef;
using rwd::sim::BodyId;
using rwd::sim::BodyKind;
using rwd::sim::Quat;
using rwd::sim::Shape;
using rwd::sim::Vec3;
using rwd::sim::World3D;
using rwd::sim::WorldConfig;

constexpr int kLevelBoxes = 10000;
constexpr int kQueries = 1000;
constexpr float kRayLength = 200.0f;
constexpr float kSweepLength = 20.0f;
constexpr float kCastSphereRadius = 0.5f;
constexpr float kCastBoxHalf = 0.5f;
constexpr float kOverlapRadius = 3.0f;
constexpr int kDynamicBodies = 200;
constexpr int kWarmupTicks = 60;
constexpr int kTimedTicks = 240;
constexpr float kTick = 1.0f / 60.0f;
constexpr float kQueryMargin = 0.001f;  // Bullet's box margin in the query level
// Agreement the check demands, and how close two hit distances must be.
constexpr double kMinAgreement = 0.99;
constexpr float kDistanceTolerance = 0.01f;

struct SplitMix64 : rwd::SplitMix64 {
  float uniform(float lo, float hi) {
    return lo + (hi - lo) * static_cast<float>(next() >> 40) * 0x1p-24f;
  }
  // Uniform over rotations (Shoemake), so no orientation is favoured. libm's
  // sin and cos may differ by an ulp between machines; both engines get the
  // same values all the same, as Bullet is given the poses Rewind kept.
  Quat rotation() {
    const float u1 = uniform(0.0f, 1.0f);
    const float a = 6.2831853f * uniform(0.0f, 1.0f);
    const float b = 6.2831853f * uniform(0.0f, 1.0f);
    const float s = std::sqrt(1.0f - u1);
    const float t = std::sqrt(u1);
    return {s * std::sin(a), s * std::cos(a), t * std::sin(b), t * std::cos(b)};
  }
};

inline btVector3 bt(Vec3 v) {
  return {v.x, v.y, v.z};
}
inline btQuaternion bt(Quat q) {
  return {q.x, q.y, q.z, q.w};
}
inline btTransform pose(Vec3 p, Quat q) {
  return btTransform(bt(q), bt(p));
}

struct BoxSpec {
  Vec3 position;
  Quat rotation;
  Vec3 half;
};

inline std::vector<BoxSpec> level_boxes() {
  SplitMix64 rng{0x5EED1E7E1ull};
  std::vector<BoxSpec> boxes(kLevelBoxes);
  for (BoxSpec& b : boxes) {
    b.half = {rng.uniform(0.25f, 2.0f), rng.uniform(0.25f, 2.0f), rng.uniform(0.25f, 2.0f)};
    b.rotation = rng.rotation();
    b.position = {rng.uniform(-200.0f, 200.0f), rng.uniform(0.0f, 40.0f),
                  rng.uniform(-200.0f, 200.0f)};
  }
  return boxes;
}

// --- Bullet ------------------------------------------------------------------

// Per-body surface values for the combine callback, as in bullet_engine.cpp.
struct Surface {
  float friction = 0.0f;
  float restitution = 0.0f;
};

inline bool combine_like_rewind(btManifoldPoint& cp, const btCollisionObjectWrapper* a, int, int,
                                const btCollisionObjectWrapper* b, int, int) {
  const auto* sa = static_cast<const Surface*>(a->getCollisionObject()->getUserPointer());
  const auto* sb = static_cast<const Surface*>(b->getCollisionObject()->getUserPointer());
  if (sa == nullptr || sb == nullptr) return false;
  cp.m_combinedFriction = std::sqrt(sa->friction * sb->friction);
  cp.m_combinedRestitution = std::max(sa->restitution, sb->restitution);
  return true;
}

struct BulletWorld {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<Surface> surfaces;  // reserved up front: bodies point into it

  explicit BulletWorld(size_t capacity) {
    surfaces.reserve(capacity);
    bodies.reserve(capacity);
    world.setGravity(btVector3(0.0f, -9.81f, 0.0f));
    world.getSolverInfo().m_numIterations = 10;
    world.getSolverInfo().m_restitutionVelocityThreshold = 1.0f;
    world.setForceUpdateAllAabbs(false);
    gContactAddedCallback = combine_like_rewind;
    gDeactivationTime = 0.5f;
  }
  ~BulletWorld() {
    for (auto it = bodies.rbegin(); it != bodies.rend(); ++it) world.removeRigidBody(it->get());
  }
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  // The mapping of bullet_engine.cpp for default materials (friction 0.6,
  // restitution 0, angular damping 0.05 /s, density 1000 kg/m^3). A box
  // gets `box_margin` when it is positive, else bullet_engine.cpp's rule.
  btRigidBody* add(const Shape& s, BodyKind kind, Vec3 position, Quat rotation, Vec3 velocity,
                   Vec3 spin, int user_index, float box_margin = 0.0f) {
    std::unique_ptr<btCollisionShape> shape;
    float volume = 0.0f;
    float extent = 0.0f;
    if (s.type == rwd::sim::ShapeType::kSphere) {
      shape = std::make_unique<btSphereShape>(s.radius);
      volume = 4.0f / 3.0f * 3.14159265f * s.radius * s.radius * s.radius;
      extent = s.radius;
    } else {
      const Vec3 h = s.half_extents;
      const float smallest = std::min(h.x, std::min(h.y, h.z));
      auto box = std::make_unique<btBoxShape>(bt(h));
      if (box->getMargin() > 0.5f * smallest) box->setMargin(0.5f * smallest);
      if (box_margin > 0.0f) box->setMargin(box_margin);
      shape = std::move(box);
      volume = 8.0f * h.x * h.y * h.z;
      extent = rwd::sim::length(h);
    }
    const bool dynamic = kind == BodyKind::kDynamic;
    const float mass = dynamic ? 1000.0f * volume : 0.0f;
    btVector3 inertia(0.0f, 0.0f, 0.0f);
    if (dynamic) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, shape.get(), inertia);
    ci.m_startWorldTransform = pose(position, rotation);
    ci.m_friction = 0.6f;
    ci.m_restitution = 0.0f;
    ci.m_angularDamping = 1.0f - std::exp(-0.05f);
    ci.m_linearSleepingThreshold = 0.05f;
    ci.m_angularSleepingThreshold = 0.05f / extent;
    auto body = std::make_unique<btRigidBody>(ci);
    surfaces.push_back({0.6f, 0.0f});
    body->setUserPointer(&surfaces.back());
    body->setUserIndex(user_index);
    body->setCollisionFlags(body->getCollisionFlags() |
                            btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    if (dynamic) {
      body->setLinearVelocity(bt(velocity));
      body->setAngularVelocity(bt(spin));
    }
    world.addRigidBody(body.get());
    btRigidBody* raw = body.get();
    shapes.push_back(std::move(shape));
    bodies.push_back(std::move(body));
    return raw;
  }

  void step() { world.stepSimulation(kTick, 0); }  // exactly one 1/60 s step
};

// --- the level in both engines ---------------------------------------------------

struct Ray {
  Vec3 origin;
  Vec3 direction;
};
struct Sweep {
  Vec3 origin;
  Quat rotation;
  Vec3 translation;
};

// A hit as either engine reports it: the level box's index, metres along.
struct Hit {
  int box = -1;
  float distance = 0.0f;
};

inline WorldConfig level_config() {
  WorldConfig config;
  config.max_bodies = 16384;  // the default 4096 refuses a 10,000-box level
  return config;
}

// Which Rewind body is which level box, both ways.
struct LevelIds {
  std::vector<int> box_of_index;  // by Rewind body index
  std::vector<BodyId> body_of_box;
};

// Adds the level to Rewind and, when given, to Bullet with the pose and size
// Rewind kept (and `bullet_margin`, see BulletWorld::add).
inline LevelIds add_level(World3D& rewind, BulletWorld* bullet, float bullet_margin) {
  LevelIds ids;
  int box = 0;
  for (const BoxSpec& b : level_boxes()) {
    BodyDef def;
    def.kind = BodyKind::kStatic;
    def.shape = Shape::make_box(b.half);
    def.position = b.position;
    def.rotation = b.rotation;
    auto id = rewind.create_body(def);
    if (!id.ok()) {
      std::fprintf(stderr, "query_bench: level box refused: %s\n",
                   std::string(id.status().message()).c_str());
      std::exit(EXIT_FAILURE);
    }
    if (ids.box_of_index.size() <= id->index) ids.box_of_index.resize(id->index + 1, -1);
    ids.box_of_index[id->index] = box;
    ids.body_of_box.push_back(*id);
    if (bullet != nullptr) {
      bullet->add(*rewind.shape(*id), BodyKind::kStatic, rewind.position(*id), rewind.rotation(*id),
                  {}, {}, box, bullet_margin);
    }
    ++box;
  }
  return ids;
}

struct Level {
  World3D rewind{level_config()};
  BulletWorld bullet{kLevelBoxes};
  std::vector<int> box_of_index;  // Rewind body index -> level box
  std::vector<BodyId> body_of_box;
  std::vector<Ray> rays;
  std::vector<Sweep> sphere_sweeps;
  std::vector<Sweep> box_sweeps;
  std::vector<Vec3> overlap_centres;
  Shape cast_sphere = Shape::make_sphere(kCastSphereRadius);
  Shape cast_box = Shape::make_box({kCastBoxHalf, kCastBoxHalf, kCastBoxHalf});
  Shape overlap_sphere = Shape::make_sphere(kOverlapRadius);
  btSphereShape bt_cast_sphere{kCastSphereRadius};
  btBoxShape bt_cast_box{btVector3(kCastBoxHalf, kCastBoxHalf, kCastBoxHalf)};
  btSphereShape bt_overlap_sphere{kOverlapRadius};
  btCollisionObject bt_overlap_object;
  // Agreement of the one-off check, per family, reported as counters.
  double agree_closest = 0.0;
  double agree_all = 0.0;
  double agree_sphere = 0.0;
  double agree_box = 0.0;
  double agree_overlap = 0.0;

  Level() {
    bt_overlap_object.setCollisionShape(&bt_overlap_sphere);
    bt_cast_box.setMargin(kQueryMargin);
  }
};

// Directions mostly downward and sideways: a camera or a gun above the level.
inline Vec3 downward_direction(SplitMix64& rng) {
  const Vec3 d{rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, -0.1f), rng.uniform(-1.0f, 1.0f)};
  return rwd::sim::normalize_or_zero(d);
}

// Sweep starts inside the level volume, at least 5 cm clear of every box:
// Rewind's contract reports a shape that starts touching at distance 0,
// Bullet's sweep promises nothing there, and a game sweeps from free space.
inline std::vector<Sweep> make_sweeps(const World3D& world, const Shape& shape, uint64_t seed) {
  SplitMix64 rng{seed};
  Shape inflated = shape;
  if (shape.type == rwd::sim::ShapeType::kSphere) {
    inflated.radius += 0.05f;
  } else {
    inflated.half_extents = shape.half_extents + Vec3{0.05f, 0.05f, 0.05f};
  }
  std::vector<Sweep> sweeps;
  std::vector<BodyId> touching;
  while (sweeps.size() < kQueries) {
    Sweep s;
    s.origin = {rng.uniform(-200.0f, 200.0f), rng.uniform(0.0f, 45.0f),
                rng.uniform(-200.0f, 200.0f)};
    s.rotation = shape.type == rwd::sim::ShapeType::kBox ? rng.rotation() : Quat{};
    s.translation = downward_direction(rng) * kSweepLength;
    if (!world.overlap(inflated, s.origin, s.rotation, {}, touching).ok() || !touching.empty()) {
      continue;
    }
    sweeps.push_back(s);
  }
  return sweeps;
}

// --- one query in each engine (the timed loops call exactly these) -----------

inline std::optional<Hit> rewind_closest(const Level& level, const Ray& ray) {
  const auto hit = level.rewind.raycast({ray.origin, ray.direction, kRayLength});
  if (!hit) return std::nullopt;
  return Hit{level.box_of_index[hit->body.index], hit->distance};
}

inline std::optional<Hit> bullet_closest(const Level& level, const Ray& ray) {
  const btVector3 from = bt(ray.origin);
  const btVector3 to = bt(ray.origin + ray.direction * kRayLength);
  btCollisionWorld::ClosestRayResultCallback cb(from, to);
  level.bullet.world.rayTest(from, to, cb);
  if (!cb.hasHit()) return std::nullopt;
  return Hit{cb.m_collisionObject->getUserIndex(), cb.m_closestHitFraction * kRayLength};
}

inline size_t rewind_all(const Level& level, const Ray& ray, std::vector<rwd::sim::RayHit>& out) {
  level.rewind.raycast_all({ray.origin, ray.direction, kRayLength}, {}, out);
  return out.size();
}

inline size_t bullet_all(const Level& level, const Ray& ray,
                         btCollisionWorld::AllHitsRayResultCallback& cb) {
  // Reset instead of constructing: a new callback would allocate its arrays
  // on every ray, where Rewind's reused vector does not.
  cb.m_rayFromWorld = bt(ray.origin);
  cb.m_rayToWorld = bt(ray.origin + ray.direction * kRayLength);
  cb.m_closestHitFraction = 1.0f;
  cb.m_collisionObject = nullptr;
  cb.m_collisionObjects.resize(0);
  cb.m_hitNormalWorld.resize(0);
  cb.m_hitPointWorld.resize(0);
  cb.m_hitFractions.resize(0);
  level.bullet.world.rayTest(cb.m_rayFromWorld, cb.m_rayToWorld, cb);
  return static_cast<size_t>(cb.m_collisionObjects.size());
}

inline std::optional<Hit> rewind_sweep(const Level& level, const Shape& shape, const Sweep& s) {
  std::optional<rwd::sim::ShapeCastHit> hit;
  (void)level.rewind.shape_cast(shape, s.origin, s.rotation, s.translation, {}, hit);
  if (!hit) return std::nullopt;
  return Hit{level.box_of_index[hit->body.index], hit->distance};
}

inline std::optional<Hit> bullet_sweep(const Level& level, const btConvexShape& shape,
                                       const Sweep& s) {
  const btTransform from = pose(s.origin, s.rotation);
  const btTransform to = pose(s.origin + s.translation, s.rotation);
  btCollisionWorld::ClosestConvexResultCallback cb(from.getOrigin(), to.getOrigin());
  level.bullet.world.convexSweepTest(&shape, from, to, cb, 0.0f);
  if (!cb.hasHit()) return std::nullopt;
  return Hit{cb.m_hitCollisionObject->getUserIndex(), cb.m_closestHitFraction * kSweepLength};
}

// Collects the level boxes contactTest reports touching or overlapping.
struct OverlapCollector final : btCollisionWorld::ContactResultCallback {
  const btCollisionObject* query = nullptr;
  std::vector<int> boxes;
  btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper* a, int, int,
                           const btCollisionObjectWrapper* b, int, int) override {
    if (cp.getDistance() > 0.0f) return 0.0f;  // near but apart: not an overlap
    const btCollisionObject* other =
        a->getCollisionObject() == query ? b->getCollisionObject() : a->getCollisionObject();
    const int box = other->getUserIndex();
    if (boxes.empty() || boxes.back() != box) boxes.push_back(box);
    return 0.0f;
  }
};

inline size_t rewind_overlap(const Level& level, Vec3 centre, std::vector<BodyId>& out) {
  (void)level.rewind.overlap(level.overlap_sphere, centre, Quat{}, {}, out);
  return out.size();
}

inline size_t bullet_overlap(Level& level, Vec3 centre, OverlapCollector& out) {
  out.boxes.clear();
  out.query = &level.bt_overlap_object;
  level.bt_overlap_object.getWorldTransform().setOrigin(bt(centre));
  level.bullet.world.contactTest(&level.bt_overlap_object, out);
  return out.boxes.size();
}

}  // namespace rwd::bench::query_level
