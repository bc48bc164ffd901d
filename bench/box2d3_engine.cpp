// SPDX-License-Identifier: MIT
// Compiled with Box2D v3's include directory only, so <box2d/box2d.h> here
// is v3's C API, never Debian's Box2D 2.4.
#include "box2d3_engine.h"

#include <box2d/box2d.h>

#include <map>
#include <string>
#include <vector>

namespace rwd::bench {

namespace {

float milli(int32_t v) {
  return static_cast<float>(v) / 1000.0f;
}

}  // namespace

struct Box2D3Engine::World {
  b2WorldId id = b2_nullWorldId;
  std::vector<b2BodyId> bodies;              // per scene body; grouped bodies share one
  std::vector<std::vector<b2BodyId>> waves;  // the bodies each wave added

  World() = default;
  World(const World&) = delete;
  World& operator=(const World&) = delete;
  // Box2D v3 holds at most 128 worlds at once: each is given back.
  ~World() {
    if (b2World_IsValid(id)) b2DestroyWorld(id);
  }

  // Creates the bodies (one per group) and the joints between them,
  // appending the bodies to `out`.
  void add(const Scene2D& scene, const std::vector<BodyDesc2D>& descs,
           const std::vector<RevoluteDesc2D>& joints, std::vector<b2BodyId>& out) const;
};

void Box2D3Engine::World::add(const Scene2D& scene, const std::vector<BodyDesc2D>& descs,
                              const std::vector<RevoluteDesc2D>& joints,
                              std::vector<b2BodyId>& out) const {
  const size_t first = out.size();
  std::map<int32_t, b2BodyId> groups;
  for (const BodyDesc2D& b : descs) {
    b2BodyId body = b2_nullBodyId;
    if (b.group >= 0) {
      auto it = groups.find(b.group);
      if (it != groups.end()) body = it->second;
    }
    if (B2_IS_NULL(body)) {
      b2BodyDef def = b2DefaultBodyDef();
      def.type = b.kind == Kind2D::kStatic      ? b2_staticBody
                 : b.kind == Kind2D::kKinematic ? b2_kinematicBody
                                                : b2_dynamicBody;
      def.position = b2Vec2{milli(b.x), milli(b.y)};
      def.linearVelocity = b2Vec2{milli(b.vx), milli(b.vy)};
      def.angularVelocity = milli(b.angular_velocity);
      def.linearDamping = milli(b.linear_damping);
      // A body made asleep must allow sleep to start so (Box2D v3 puts the
      // others in the awake set); the world's sleeping stays off, so once
      // woken it never sleeps again, as in the other adapters.
      def.isAwake = b.awake;
      def.enableSleep = !b.awake;
      body = b2CreateBody(id, &def);
      if (b.group >= 0) groups[b.group] = body;
    }
    b2ShapeDef shape = b2DefaultShapeDef();
    shape.density =
        b.kind == Kind2D::kDynamic ? milli(b.density > 0 ? b.density : scene.density) : 0.0f;
    shape.material.friction = milli(b.friction >= 0 ? b.friction : scene.friction);
    shape.material.restitution = 0.0f;
    shape.filter.categoryBits = b.layer;
    shape.filter.maskBits = b.mask;
    const b2Vec2 centre{milli(b.cx), milli(b.cy)};
    if (b.radius > 0 && b.capsule_y0 != b.capsule_y1) {
      const b2Capsule capsule{b2Vec2{centre.x, milli(b.capsule_y0)},
                              b2Vec2{centre.x, milli(b.capsule_y1)}, milli(b.radius)};
      b2CreateCapsuleShape(body, &shape, &capsule);
    } else if (b.radius > 0) {
      const b2Circle circle{centre, milli(b.radius)};
      b2CreateCircleShape(body, &shape, &circle);
    } else {
      const b2Polygon box = b2MakeOffsetBox(milli(b.hx), milli(b.hy), centre, b2Rot_identity);
      b2CreatePolygonShape(body, &shape, &box);
    }
    out.push_back(body);
  }
  for (const RevoluteDesc2D& j : joints) {
    // What Box2D 2.4's b2RevoluteJointDef::Initialize does: the world
    // anchor in each body's frame, and the bodies' angle between them,
    // plus the scene's reference.
    const b2BodyId a = out[first + j.a], b = out[first + j.b];
    const b2Vec2 anchor{milli(j.x), milli(j.y)};
    b2RevoluteJointDef def = b2DefaultRevoluteJointDef();
    def.bodyIdA = a;
    def.bodyIdB = b;
    def.localAnchorA = b2Body_GetLocalPoint(a, anchor);
    def.localAnchorB = b2Body_GetLocalPoint(b, anchor);
    def.referenceAngle =
        b2RelativeAngle(b2Body_GetRotation(b), b2Body_GetRotation(a)) + milli(j.reference);
    def.enableLimit = j.limit;
    def.lowerAngle = milli(j.lower);
    def.upperAngle = milli(j.upper);
    def.enableMotor = j.friction_torque > 0;
    def.maxMotorTorque = milli(j.friction_torque);
    def.enableSpring = j.hertz > 0;
    def.hertz = milli(j.hertz);
    def.dampingRatio = milli(j.damping_ratio);
    b2CreateRevoluteJoint(id, &def);
  }
}

Box2D3Engine::Box2D3Engine(int substeps) : substeps_(substeps) {}

Box2D3Engine::~Box2D3Engine() = default;

std::string Box2D3Engine::settings() const {
  return "substeps=" + std::to_string(substeps_);
}

bool Box2D3Engine::build(const Scene2D& scene, std::string& /*error*/) {
  world_.reset();  // the old world goes before the new one is made
  world_ = std::make_unique<World>();
  b2WorldDef world_def = b2DefaultWorldDef();
  world_def.gravity = b2Vec2{0.0f, milli(scene.gravity)};
  // Every body stays awake, as in the other adapters, so that all engines
  // do the same work. workerCount stays at its default: one thread, no task
  // system. Continuous collision stays on (Box2D's default).
  world_def.enableSleep = false;
  world_->id = b2CreateWorld(&world_def);
  world_->waves.assign(scene.waves.size(), {});
  world_->add(scene, scene.bodies, scene.joints, world_->bodies);
  return true;
}

bool Box2D3Engine::add_wave(const Scene2D& scene, uint32_t wave, std::string& /*error*/) {
  const Wave2D& w = scene.waves[wave];
  world_->add(scene, w.bodies, w.joints, world_->waves[wave]);
  return true;
}

void Box2D3Engine::remove_wave(uint32_t wave) {
  for (const b2BodyId body : world_->waves[wave]) {
    if (b2Body_IsValid(body)) b2DestroyBody(body);  // grouped bodies repeat
  }
  world_->waves[wave].clear();
}

void Box2D3Engine::step() {
  b2World_Step(world_->id, 1.0f / 60.0f, substeps_);
}

namespace {

Pose2D pose_of(b2BodyId body) {
  const b2Vec2 p = b2Body_GetPosition(body);
  return {p.x, p.y, b2Rot_GetAngle(b2Body_GetRotation(body))};
}

}  // namespace

Pose2D Box2D3Engine::pose(uint32_t index) const {
  return pose_of(world_->bodies[index]);
}

Pose2D Box2D3Engine::wave_pose(uint32_t wave, uint32_t index) const {
  return pose_of(world_->waves[wave][index]);
}

bool Box2D3Engine::raycast(double x0, double y0, double x1, double y1, double& fraction) const {
  const b2Vec2 origin{static_cast<float>(x0), static_cast<float>(y0)};
  const b2Vec2 translation{static_cast<float>(x1 - x0), static_cast<float>(y1 - y0)};
  const b2RayResult hit =
      b2World_CastRayClosest(world_->id, origin, translation, b2DefaultQueryFilter());
  if (!hit.hit) return false;
  fraction = hit.fraction;
  return true;
}

}  // namespace rwd::bench
