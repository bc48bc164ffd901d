// SPDX-License-Identifier: MIT
// Scene queries and stepping in a large static level, Rewind beside Bullet in
// the same process on the same data.
//
// The level: 10,000 static boxes (SplitMix64, sizes 0.5-4 m, random
// rotations, centres over 400 m x 400 m at heights 0-40 m). Rewind builds it
// first and Bullet gets the poses and sizes Rewind kept (quantized on
// creation), so both engines hold the same solids.
//
// Query families, each iteration 1,000 queries from a fixed list:
// - Raycast/closest: World3D::raycast vs rayTest + ClosestRayResultCallback.
// - Raycast/all: World3D::raycast_all (sorted near to far) vs rayTest +
//   AllHitsRayResultCallback (unsorted: sorting is not Bullet's contract).
//   Both reuse their result storage from ray to ray.
// - ShapeCast/sphere, ShapeCast/box: World3D::shape_cast vs convexSweepTest +
//   ClosestConvexResultCallback (no allowed penetration), sweeps of 20 m
//   from free space inside the level.
// - Overlap/sphere: World3D::overlap vs contactTest with a free-standing
//   btCollisionObject. contactTest is Bullet's one-shot "what touches this
//   shape here" (broadphase box test, then the pair's algorithm per
//   candidate), which is what overlap() answers; a btPairCachingGhostObject
//   answers it only after a broadphase update per move and still needs the
//   same narrowphase, so it is the less direct equivalent. Bullet reports
//   points out to its contact threshold; only those at distance <= 0
//   (touching or overlapping, Rewind's rule) count.
// Bullet's query level gives its boxes a 1 mm collision margin instead of the
// default 4 cm: its sweeps run GJK on the shrunk box plus the margin, a box
// with edges rounded by the margin, and with 4 cm they hit 1-20 cm late near
// edges (a third of box sweeps differ by more than 1 cm), which is no longer
// the same question. Rays and overlaps do not depend on it. Bullet's tree is
// built by insertion; it gets btDbvtBroadphase::optimize() (a top-down
// rebuild) before timing, as Rewind rebuilds its query tree on the first
// query after an edit. The first query benchmark to run compares the two
// engines' answers once (not timed) and stops the run if fewer than 99% of
// any family agree (the rule is in check_agreement).
//
// Step families: 200 dynamic boxes and spheres dropped over the level (plus a
// ground slab under it) vs over the ground slab alone; 60 warm-up ticks, then
// 240 timed ticks (the fall into the level and the first landings). Rewind
// uses the default WorldConfig except max_bodies (the default 4096 refuses a
// 10,000-body level). Bullet is set up like bench/bullet_engine.cpp: same
// gravity, one 1/60 s step per tick, btDbvtBroadphase, 10 iterations, its
// default margins, Rewind's friction and restitution combination, damping
// and sleeping thresholds. One difference: setForceUpdateAllAabbs(false),
// what a Bullet game with a large static level sets; by default Bullet
// recomputes every static box's bounds every step and moves each one back
// into the broadphase's dynamic tree.
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

#include "rewind/sim/world3d.h"

namespace {

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

struct SplitMix64 {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
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

btVector3 bt(Vec3 v) {
  return {v.x, v.y, v.z};
}
btQuaternion bt(Quat q) {
  return {q.x, q.y, q.z, q.w};
}
btTransform pose(Vec3 p, Quat q) {
  return btTransform(bt(q), bt(p));
}

struct BoxSpec {
  Vec3 position;
  Quat rotation;
  Vec3 half;
};

std::vector<BoxSpec> level_boxes() {
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

bool combine_like_rewind(btManifoldPoint& cp, const btCollisionObjectWrapper* a, int, int,
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

WorldConfig level_config() {
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
LevelIds add_level(World3D& rewind, BulletWorld* bullet, float bullet_margin) {
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
Vec3 downward_direction(SplitMix64& rng) {
  const Vec3 d{rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, -0.1f), rng.uniform(-1.0f, 1.0f)};
  return rwd::sim::normalize_or_zero(d);
}

// Sweep starts inside the level volume, at least 5 cm clear of every box:
// Rewind's contract reports a shape that starts touching at distance 0,
// Bullet's sweep promises nothing there, and a game sweeps from free space.
std::vector<Sweep> make_sweeps(const World3D& world, const Shape& shape, uint64_t seed) {
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

std::optional<Hit> rewind_closest(const Level& level, const Ray& ray) {
  const auto hit = level.rewind.raycast({ray.origin, ray.direction, kRayLength});
  if (!hit) return std::nullopt;
  return Hit{level.box_of_index[hit->body.index], hit->distance};
}

std::optional<Hit> bullet_closest(const Level& level, const Ray& ray) {
  const btVector3 from = bt(ray.origin);
  const btVector3 to = bt(ray.origin + ray.direction * kRayLength);
  btCollisionWorld::ClosestRayResultCallback cb(from, to);
  level.bullet.world.rayTest(from, to, cb);
  if (!cb.hasHit()) return std::nullopt;
  return Hit{cb.m_collisionObject->getUserIndex(), cb.m_closestHitFraction * kRayLength};
}

size_t rewind_all(const Level& level, const Ray& ray, std::vector<rwd::sim::RayHit>& out) {
  level.rewind.raycast_all({ray.origin, ray.direction, kRayLength}, {}, out);
  return out.size();
}

size_t bullet_all(const Level& level, const Ray& ray,
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

std::optional<Hit> rewind_sweep(const Level& level, const Shape& shape, const Sweep& s) {
  std::optional<rwd::sim::ShapeCastHit> hit;
  (void)level.rewind.shape_cast(shape, s.origin, s.rotation, s.translation, {}, hit);
  if (!hit) return std::nullopt;
  return Hit{level.box_of_index[hit->body.index], hit->distance};
}

std::optional<Hit> bullet_sweep(const Level& level, const btConvexShape& shape, const Sweep& s) {
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

size_t rewind_overlap(const Level& level, Vec3 centre, std::vector<BodyId>& out) {
  (void)level.rewind.overlap(level.overlap_sphere, centre, Quat{}, {}, out);
  return out.size();
}

size_t bullet_overlap(Level& level, Vec3 centre, OverlapCollector& out) {
  out.boxes.clear();
  out.query = &level.bt_overlap_object;
  level.bt_overlap_object.getWorldTransform().setOrigin(bt(centre));
  level.bullet.world.contactTest(&level.bt_overlap_object, out);
  return out.boxes.size();
}

// --- the agreement check --------------------------------------------------------

// Distance from `point` to the surface of level box `box` (Rewind's exact
// point query, so the yardstick is the solid both engines hold).
float surface_gap(const Level& level, int box, Vec3 point) {
  const auto hit = level.rewind.signed_distance(level.body_of_box[static_cast<size_t>(box)], point);
  return hit ? std::fabs(hit->distance) : std::numeric_limits<float>::infinity();
}

// Tallies of one family's check.
struct Tally {
  int strict = 0;    // same hit or miss, same box, distances within 1 cm
  int accepted = 0;  // strict, or within Bullet's documented tolerance (rays)
  int rewind_hits = 0;
  float largest_m = 0.0f;  // largest distance difference on the same box
};

bool strictly_same(const std::optional<Hit>& a, const std::optional<Hit>& b, Tally& t) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  if (a->box != b->box) return false;
  const float diff = std::fabs(a->distance - b->distance);
  t.largest_m = std::max(t.largest_m, diff);
  return diff <= kDistanceTolerance;
}

// Bullet's ray test against a convex shape (btSubsimplexConvexCast, its
// default) stops once the ray point is within 1 cm of the surface
// (squared distance below 1e-4), so its hit lies up to 1 cm off the surface
// along the normal (several cm along a slanting ray) and a ray passing within
// 1 cm of an edge counts as a hit. A Bullet hit is accepted when its point is
// within 1 cm of the box it names and no farther than Rewind's first hit; a
// hit Rewind finds must be found by Bullet too.
bool ray_accepted(const Level& level, const Ray& ray, const std::optional<Hit>& rewind,
                  const std::optional<Hit>& bullet) {
  if (!bullet) return !rewind;
  const Vec3 point = ray.origin + ray.direction * bullet->distance;
  if (surface_gap(level, bullet->box, point) > kDistanceTolerance) return false;
  return !rewind || bullet->distance <= rewind->distance + kDistanceTolerance;
}

double report(const char* family, const Tally& t) {
  const double accepted = static_cast<double>(t.accepted) / kQueries;
  std::fprintf(stderr,
               "query_bench: %-16s %4d/%d strictly same (hit or miss, body, distance within "
               "1 cm), %4d/%d accepted; %d hits in Rewind; largest distance difference on the "
               "same body %.1f mm\n",
               family, t.strict, kQueries, t.accepted, kQueries, t.rewind_hits,
               static_cast<double>(t.largest_m) * 1000.0);
  if (accepted < kMinAgreement) {
    std::fprintf(stderr,
                 "query_bench: %s: Rewind and Bullet agree on %.1f%% of the queries (need "
                 "%.0f%%), so they would not be doing the same work; stopping.\n",
                 family, accepted * 100.0, kMinAgreement * 100.0);
    std::exit(EXIT_FAILURE);
  }
  return accepted * 100.0;
}

void check_agreement(Level& level) {
  Tally closest;
  for (const Ray& r : level.rays) {
    const auto a = rewind_closest(level, r);
    const auto b = bullet_closest(level, r);
    closest.rewind_hits += a.has_value();
    const bool strict = strictly_same(a, b, closest);
    closest.strict += strict;
    closest.accepted += strict || ray_accepted(level, r, a, b);
  }
  level.agree_closest = report("Raycast/closest", closest);

  // Every body along the ray: each Rewind hit needs a Bullet hit on the same
  // body, and each Bullet hit must pass the closest-hit rule on its own.
  Tally all;
  std::vector<rwd::sim::RayHit> rewind_hits;
  btCollisionWorld::AllHitsRayResultCallback cb({}, {});
  for (const Ray& r : level.rays) {
    rewind_all(level, r, rewind_hits);
    bullet_all(level, r, cb);
    std::vector<Hit> x;
    std::vector<Hit> y;
    for (const auto& h : rewind_hits) x.push_back({level.box_of_index[h.body.index], h.distance});
    for (int i = 0; i < cb.m_collisionObjects.size(); ++i) {
      y.push_back({cb.m_collisionObjects[i]->getUserIndex(), cb.m_hitFractions[i] * kRayLength});
    }
    const auto by_box = [](const Hit& l, const Hit& h) { return l.box < h.box; };
    std::sort(x.begin(), x.end(), by_box);
    std::sort(y.begin(), y.end(), by_box);
    all.rewind_hits += !x.empty();
    bool strict = x.size() == y.size();
    for (size_t i = 0; strict && i < x.size(); ++i) strict = strictly_same(x[i], y[i], all);
    bool accepted = strict;
    if (!accepted) {
      accepted = true;
      for (const Hit& h : x) {
        accepted = accepted && std::binary_search(y.begin(), y.end(), h, by_box);
      }
      for (const Hit& h : y) {
        const auto same = std::lower_bound(x.begin(), x.end(), h, by_box);
        const bool in_x = same != x.end() && same->box == h.box;
        accepted =
            accepted && ray_accepted(level, r, in_x ? std::optional<Hit>(*same) : std::nullopt, h);
      }
    }
    all.strict += strict;
    all.accepted += accepted;
  }
  level.agree_all = report("Raycast/all", all);

  const auto sweeps = [&](const char* family, const Shape& shape, const btConvexShape& bt_shape,
                          const std::vector<Sweep>& list) {
    Tally t;
    for (const Sweep& s : list) {
      const auto a = rewind_sweep(level, shape, s);
      t.rewind_hits += a.has_value();
      const bool strict = strictly_same(a, bullet_sweep(level, bt_shape, s), t);
      t.strict += strict;
      t.accepted += strict;
    }
    return report(family, t);
  };
  level.agree_sphere =
      sweeps("ShapeCast/sphere", level.cast_sphere, level.bt_cast_sphere, level.sphere_sweeps);
  level.agree_box = sweeps("ShapeCast/box", level.cast_box, level.bt_cast_box, level.box_sweeps);

  Tally overlap;
  std::vector<BodyId> ids;
  OverlapCollector collector;
  for (const Vec3& c : level.overlap_centres) {
    rewind_overlap(level, c, ids);
    bullet_overlap(level, c, collector);
    std::vector<int> x;
    for (BodyId id : ids) x.push_back(level.box_of_index[id.index]);
    std::sort(x.begin(), x.end());
    std::sort(collector.boxes.begin(), collector.boxes.end());
    overlap.rewind_hits += !x.empty();
    const bool same = x == collector.boxes;
    overlap.strict += same;
    overlap.accepted += same;
  }
  level.agree_overlap = report("Overlap/sphere", overlap);
}

// Built on first use by a query benchmark, so a filter that runs only the
// step benchmarks skips it.
Level& level() {
  static std::unique_ptr<Level> instance = [] {
    auto l = std::make_unique<Level>();
    LevelIds ids = add_level(l->rewind, &l->bullet, kQueryMargin);
    l->box_of_index = std::move(ids.box_of_index);
    l->body_of_box = std::move(ids.body_of_box);
    l->bullet.broadphase.optimize();
    SplitMix64 rng{0xACE0F5BA5Eull};
    for (int i = 0; i < kQueries; ++i) {
      const Vec3 origin{rng.uniform(-200.0f, 200.0f), rng.uniform(45.0f, 60.0f),
                        rng.uniform(-200.0f, 200.0f)};
      l->rays.push_back({origin, downward_direction(rng)});
      l->overlap_centres.push_back(
          {rng.uniform(-200.0f, 200.0f), rng.uniform(0.0f, 40.0f), rng.uniform(-200.0f, 200.0f)});
    }
    l->sphere_sweeps = make_sweeps(l->rewind, l->cast_sphere, 0x5111E5ull);
    l->box_sweeps = make_sweeps(l->rewind, l->cast_box, 0xB0C5ull);
    check_agreement(*l);
    return l;
  }();
  return *instance;
}

// --- query benchmarks ---------------------------------------------------------

void finish(benchmark::State& state, size_t found, double agree_pct) {
  state.SetItemsProcessed(state.iterations() * kQueries);
  state.counters["found_per_query"] =
      static_cast<double>(found) / static_cast<double>(state.iterations() * kQueries);
  state.counters["agree_pct"] = agree_pct;
}

void raycast_closest_rewind(benchmark::State& state) {
  const Level& l = level();
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays) found += rewind_closest(l, r).has_value();
  }
  finish(state, found, l.agree_closest);
}
void raycast_closest_bullet(benchmark::State& state) {
  const Level& l = level();
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays) found += bullet_closest(l, r).has_value();
  }
  finish(state, found, l.agree_closest);
}
void raycast_all_rewind(benchmark::State& state) {
  const Level& l = level();
  std::vector<rwd::sim::RayHit> out;
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays) found += rewind_all(l, r, out);
  }
  finish(state, found, l.agree_all);
}
void raycast_all_bullet(benchmark::State& state) {
  const Level& l = level();
  btCollisionWorld::AllHitsRayResultCallback cb({}, {});
  size_t found = 0;
  for (auto _ : state) {
    for (const Ray& r : l.rays) found += bullet_all(l, r, cb);
  }
  finish(state, found, l.agree_all);
}
void shape_cast_rewind(benchmark::State& state, bool box) {
  const Level& l = level();
  const Shape& shape = box ? l.cast_box : l.cast_sphere;
  const std::vector<Sweep>& sweeps = box ? l.box_sweeps : l.sphere_sweeps;
  size_t found = 0;
  for (auto _ : state) {
    for (const Sweep& s : sweeps) found += rewind_sweep(l, shape, s).has_value();
  }
  finish(state, found, box ? l.agree_box : l.agree_sphere);
}
void shape_cast_bullet(benchmark::State& state, bool box) {
  const Level& l = level();
  const btConvexShape& shape =
      box ? static_cast<const btConvexShape&>(l.bt_cast_box) : l.bt_cast_sphere;
  const std::vector<Sweep>& sweeps = box ? l.box_sweeps : l.sphere_sweeps;
  size_t found = 0;
  for (auto _ : state) {
    for (const Sweep& s : sweeps) found += bullet_sweep(l, shape, s).has_value();
  }
  finish(state, found, box ? l.agree_box : l.agree_sphere);
}
void overlap_rewind(benchmark::State& state) {
  const Level& l = level();
  std::vector<BodyId> out;
  size_t found = 0;
  for (auto _ : state) {
    for (const Vec3& c : l.overlap_centres) found += rewind_overlap(l, c, out);
  }
  finish(state, found, l.agree_overlap);
}
void overlap_bullet(benchmark::State& state) {
  Level& l = level();
  OverlapCollector out;
  size_t found = 0;
  for (auto _ : state) {
    for (const Vec3& c : l.overlap_centres) found += bullet_overlap(l, c, out);
  }
  finish(state, found, l.agree_overlap);
}

// --- step benchmarks ------------------------------------------------------------

struct Dropped {
  Shape shape;
  Vec3 position;
  Quat rotation;
  Vec3 velocity;
  Vec3 spin;
};

// Half boxes, half spheres over the middle 300 m x 300 m, just above the
// level's top, drifting slowly.
std::vector<Dropped> dropped_bodies() {
  SplitMix64 rng{0xD809ull};
  std::vector<Dropped> out(kDynamicBodies);
  for (size_t i = 0; i < out.size(); ++i) {
    Dropped& d = out[i];
    d.shape = i % 2 == 0 ? Shape::make_box({rng.uniform(0.2f, 0.5f), rng.uniform(0.2f, 0.5f),
                                            rng.uniform(0.2f, 0.5f)})
                         : Shape::make_sphere(rng.uniform(0.2f, 0.5f));
    d.position = {rng.uniform(-150.0f, 150.0f), rng.uniform(45.0f, 60.0f),
                  rng.uniform(-150.0f, 150.0f)};
    d.rotation = rng.rotation();
    d.velocity = {rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 0.0f), rng.uniform(-1.0f, 1.0f)};
    d.spin = {rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)};
  }
  return out;
}

// A ground slab whose top is y = 0, under the whole level.
constexpr Vec3 kGroundHalf{250.0f, 1.0f, 250.0f};
constexpr Vec3 kGroundCentre{0.0f, -1.0f, 0.0f};

void step_rewind(benchmark::State& state, bool with_level) {
  World3D world(level_config());
  BodyDef ground;
  ground.kind = BodyKind::kStatic;
  ground.shape = Shape::make_box(kGroundHalf);
  ground.position = kGroundCentre;
  bool ok = world.create_body(ground).ok();
  if (with_level) add_level(world, nullptr, 0.0f);
  for (const Dropped& d : dropped_bodies()) {
    BodyDef def;
    def.shape = d.shape;
    def.position = d.position;
    def.rotation = d.rotation;
    def.linear_velocity = d.velocity;
    def.angular_velocity = d.spin;
    ok = ok && world.create_body(def).ok();
  }
  if (!ok) {
    state.SkipWithError("a body was refused");
    return;
  }
  for (int t = 0; t < kWarmupTicks; ++t) world.step();
  for (auto _ : state) world.step();
  state.counters["bodies"] = world.body_count();
  state.counters["awake_at_end"] = world.stats().awake_bodies;
  state.counters["contacts_at_end"] = world.stats().contact_points;
}

void step_bullet(benchmark::State& state, bool with_level) {
  BulletWorld world(kLevelBoxes + kDynamicBodies + 1);
  world.add(Shape::make_box(kGroundHalf), BodyKind::kStatic, kGroundCentre, Quat{}, {}, {}, -1);
  if (with_level) {
    World3D rewind(level_config());  // the source of the quantized level poses
    add_level(rewind, &world, 0.0f);
  }
  // The same quantized start state Rewind gets.
  World3D source(level_config());
  for (const Dropped& d : dropped_bodies()) {
    BodyDef def;
    def.shape = d.shape;
    def.position = d.position;
    def.rotation = d.rotation;
    def.linear_velocity = d.velocity;
    def.angular_velocity = d.spin;
    const auto id = source.create_body(def);
    if (!id.ok()) {
      state.SkipWithError("a body was refused");
      return;
    }
    world.add(*source.shape(*id), BodyKind::kDynamic, source.position(*id), source.rotation(*id),
              source.linear_velocity(*id), source.angular_velocity(*id), -1);
  }
  for (int t = 0; t < kWarmupTicks; ++t) world.step();
  for (auto _ : state) world.step();
  uint32_t awake = 0;
  for (const auto& b : world.bodies) awake += !b->isStaticOrKinematicObject() && b->isActive();
  int contacts = 0;
  for (int m = 0; m < world.dispatcher.getNumManifolds(); ++m) {
    contacts += world.dispatcher.getManifoldByIndexInternal(m)->getNumContacts();
  }
  state.counters["bodies"] = static_cast<double>(world.bodies.size());
  state.counters["awake_at_end"] = awake;
  state.counters["contacts_at_end"] = contacts;
}

void register_all() {
  using benchmark::RegisterBenchmark;
  for (auto* b : {
           RegisterBenchmark("Raycast/closest/Rewind", raycast_closest_rewind),
           RegisterBenchmark("Raycast/closest/Bullet", raycast_closest_bullet),
           RegisterBenchmark("Raycast/all/Rewind", raycast_all_rewind),
           RegisterBenchmark("Raycast/all/Bullet", raycast_all_bullet),
           RegisterBenchmark("ShapeCast/sphere/Rewind", shape_cast_rewind, false),
           RegisterBenchmark("ShapeCast/sphere/Bullet", shape_cast_bullet, false),
           RegisterBenchmark("ShapeCast/box/Rewind", shape_cast_rewind, true),
           RegisterBenchmark("ShapeCast/box/Bullet", shape_cast_bullet, true),
           RegisterBenchmark("Overlap/sphere/Rewind", overlap_rewind),
           RegisterBenchmark("Overlap/sphere/Bullet", overlap_bullet),
       }) {
    b->Unit(benchmark::kMicrosecond);  // per iteration of 1,000 queries
  }
  // One iteration is one tick, and every run times the same 240 ticks of the
  // same drop (ticks 60-300), so the fall, the first touches and the landings
  // weigh the same in both engines' averages.
  for (auto* b : {
           RegisterBenchmark("Step/level/Rewind", step_rewind, true),
           RegisterBenchmark("Step/level/Bullet", step_bullet, true),
           RegisterBenchmark("Step/ground/Rewind", step_rewind, false),
           RegisterBenchmark("Step/ground/Bullet", step_bullet, false),
       }) {
    b->Iterations(kTimedTicks)->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
