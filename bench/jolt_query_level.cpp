// SPDX-License-Identifier: MIT
// The level is a PhysicsSystem of static bodies that is never stepped:
// Jolt's queries go through its NarrowPhaseQuery, which needs the system's
// broadphase.
#include "jolt_query_level.h"

// Jolt.h (through jolt_setup.h) first.
#include "jolt_setup.h"

#include <Jolt/Physics/Body/BodyCreationSettings.h>
#include <Jolt/Physics/Collision/CastResult.h>
#include <Jolt/Physics/Collision/CollideShape.h>
#include <Jolt/Physics/Collision/CollisionCollectorImpl.h>
#include <Jolt/Physics/Collision/NarrowPhaseQuery.h>
#include <Jolt/Physics/Collision/RayCast.h>
#include <Jolt/Physics/Collision/Shape/BoxShape.h>
#include <Jolt/Physics/Collision/Shape/SphereShape.h>
#include <Jolt/Physics/Collision/ShapeCast.h>
#include <Jolt/Physics/PhysicsSystem.h>

namespace rwd::bench {

namespace {

JPH::Vec3 jv(sim::Vec3 v) {
  return {v.x, v.y, v.z};
}
JPH::Quat jq(sim::Quat q) {
  const sim::Quat n = sim::normalize(q);
  return {n.x, n.y, n.z, n.w};
}

}  // namespace

struct JoltQueryLevel::World {
  jolt_setup::BroadPhaseLayers layers;
  jolt_setup::ObjectVsBroadPhase object_vs_broad_phase;
  jolt_setup::ObjectPairs object_pairs;
  JPH::PhysicsSystem system;
  std::vector<JPH::BodyID> bodies;
  std::vector<int> box_of_index;  // by BodyID::GetIndex()
  // Reused from query to query, as Rewind's and Bullet's result storage is.
  JPH::AllHitCollisionCollector<JPH::CastRayCollector> ray_hits;
  JPH::AllHitCollisionCollector<JPH::CollideShapeCollector> overlaps;
  // The query shapes, made when they change (a query's cost is the query,
  // not making its shape).
  JPH::RefConst<JPH::Shape> cast_shape;
  sim::Shape cast_key;
  JPH::RefConst<JPH::Shape> overlap_sphere;
  float overlap_radius = -1.0f;

  int box_of(const JPH::BodyID& id) const { return box_of_index[id.GetIndex()]; }

  ~World() {
    JPH::BodyInterface& api = system.GetBodyInterfaceNoLock();
    for (const JPH::BodyID& id : bodies) {
      api.RemoveBody(id);
      api.DestroyBody(id);
    }
  }
};

JoltQueryLevel::JoltQueryLevel(std::span<const JoltLevelBox> boxes)
    : world_(std::make_unique<World>()) {
  jolt_setup::init_once();
  const auto count = static_cast<JPH::uint>(boxes.size());
  world_->system.Init(count, 0, 1024, 1024, world_->layers, world_->object_vs_broad_phase,
                      world_->object_pairs);
  JPH::BodyInterface& api = world_->system.GetBodyInterfaceNoLock();
  for (size_t i = 0; i < boxes.size(); ++i) {
    const JoltLevelBox& b = boxes[i];
    JPH::BodyCreationSettings s(new JPH::BoxShape(jv(b.half_extents)), jv(b.position),
                                jq(b.rotation), JPH::EMotionType::Static, jolt_setup::kStaticLayer);
    const JPH::BodyID id = api.CreateAndAddBody(s, JPH::EActivation::DontActivate);
    if (world_->box_of_index.size() <= id.GetIndex())
      world_->box_of_index.resize(id.GetIndex() + 1);
    world_->box_of_index[id.GetIndex()] = static_cast<int>(i);
    world_->bodies.push_back(id);
  }
  world_->system.OptimizeBroadPhase();
}

JoltQueryLevel::~JoltQueryLevel() = default;

std::optional<JoltLevelHit> JoltQueryLevel::closest(sim::Vec3 origin, sim::Vec3 direction,
                                                    float length) const {
  const JPH::RRayCast ray{jv(origin), jv(direction * length)};
  JPH::RayCastResult hit;
  if (!world_->system.GetNarrowPhaseQueryNoLock().CastRay(ray, hit)) return std::nullopt;
  return JoltLevelHit{world_->box_of(hit.mBodyID), hit.mFraction * length};
}

size_t JoltQueryLevel::all(sim::Vec3 origin, sim::Vec3 direction, float length,
                           std::vector<JoltLevelHit>& out) {
  const JPH::RRayCast ray{jv(origin), jv(direction * length)};
  world_->ray_hits.Reset();
  world_->system.GetNarrowPhaseQueryNoLock().CastRay(ray, JPH::RayCastSettings(), world_->ray_hits);
  out.clear();
  for (const JPH::RayCastResult& h : world_->ray_hits.mHits) {
    out.push_back({world_->box_of(h.mBodyID), h.mFraction * length});
  }
  return out.size();
}

std::optional<JoltLevelHit> JoltQueryLevel::cast(const sim::Shape& shape, sim::Vec3 origin,
                                                 sim::Quat rotation, sim::Vec3 translation) {
  const sim::Shape& key = world_->cast_key;
  if (world_->cast_shape == nullptr || shape.type != key.type || shape.radius != key.radius ||
      !(shape.half_extents == key.half_extents)) {
    if (shape.type == sim::ShapeType::kSphere) {
      world_->cast_shape = new JPH::SphereShape(shape.radius);
    } else {
      world_->cast_shape = new JPH::BoxShape(jv(shape.half_extents));
    }
    world_->cast_key = shape;
  }
  const JPH::RShapeCast cast(world_->cast_shape, JPH::Vec3::sReplicate(1.0f),
                             JPH::RMat44::sRotationTranslation(jq(rotation), jv(origin)),
                             jv(translation));
  JPH::ClosestHitCollisionCollector<JPH::CastShapeCollector> hit;
  world_->system.GetNarrowPhaseQueryNoLock().CastShape(cast, JPH::ShapeCastSettings(),
                                                       JPH::RVec3::sZero(), hit);
  if (!hit.HadHit()) return std::nullopt;
  return JoltLevelHit{world_->box_of(hit.mHit.mBodyID2),
                      hit.mHit.mFraction * sim::length(translation)};
}

size_t JoltQueryLevel::overlap(sim::Vec3 centre, float radius, std::vector<int>& out) {
  if (radius != world_->overlap_radius) {
    world_->overlap_sphere = new JPH::SphereShape(radius);
    world_->overlap_radius = radius;
  }
  world_->overlaps.Reset();
  world_->system.GetNarrowPhaseQueryNoLock().CollideShape(
      world_->overlap_sphere, JPH::Vec3::sReplicate(1.0f), JPH::RMat44::sTranslation(jv(centre)),
      JPH::CollideShapeSettings(), JPH::RVec3::sZero(), world_->overlaps);
  out.clear();
  for (const JPH::CollideShapeResult& h : world_->overlaps.mHits) {
    out.push_back(world_->box_of(h.mBodyID2));
  }
  return out.size();
}

}  // namespace rwd::bench
