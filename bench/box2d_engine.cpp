// SPDX-License-Identifier: MIT
#include "box2d_engine.h"

#include <box2d/box2d.h>

#include <map>
#include <string>

namespace rwd::bench {

namespace {

float milli(int32_t v) {
  return static_cast<float>(v) / 1000.0f;
}

}  // namespace

Box2DEngine::Box2DEngine(int velocity_iterations, int position_iterations, bool continuous)
    : velocity_(velocity_iterations), position_(position_iterations), continuous_(continuous) {}

Box2DEngine::~Box2DEngine() = default;

std::string Box2DEngine::settings() const {
  return "velocity=" + std::to_string(velocity_) + " position=" + std::to_string(position_) +
         (continuous_ ? "" : " continuous=0");
}

bool Box2DEngine::build(const Scene2D& scene, std::string& error) {
  bodies_.clear();
  world_.reset();
  if (scene.joint_springs || !scene.waves.empty()) {
    error = "box2d: Box2D 2.4.1's revolute joints have no spring (scene " + scene.name + ")";
    return false;
  }
  for (const BodyDesc2D& b : scene.bodies) {
    if (b.radius > 0 && b.capsule_y0 != b.capsule_y1) {
      error = "box2d: Box2D 2.4.1 has no capsule (scene " + scene.name + ")";
      return false;
    }
  }
  world_ = std::make_unique<b2World>(b2Vec2(0.0f, milli(scene.gravity)));
  // Both engines keep every body awake (the Rewind adapter turns its
  // sleeping off too), so they do the same work.
  world_->SetAllowSleeping(false);
  world_->SetContinuousPhysics(continuous_);
  std::map<int32_t, b2Body*> groups;
  for (const BodyDesc2D& b : scene.bodies) {
    b2Body* body = nullptr;
    if (b.group >= 0) {
      auto it = groups.find(b.group);
      if (it != groups.end()) body = it->second;
    }
    if (body == nullptr) {
      b2BodyDef def;
      def.type = b.kind == Kind2D::kStatic      ? b2_staticBody
                 : b.kind == Kind2D::kKinematic ? b2_kinematicBody
                                                : b2_dynamicBody;
      def.position.Set(milli(b.x), milli(b.y));
      def.linearVelocity.Set(milli(b.vx), milli(b.vy));
      def.angularVelocity = milli(b.angular_velocity);
      def.linearDamping = milli(b.linear_damping);
      def.allowSleep = false;
      // A body made asleep stays so until a contact or joint wakes it.
      def.awake = b.awake;
      body = world_->CreateBody(&def);
      if (b.group >= 0) groups[b.group] = body;
    }
    b2PolygonShape box;
    box.SetAsBox(milli(b.hx), milli(b.hy), b2Vec2(milli(b.cx), milli(b.cy)), 0.0f);
    b2CircleShape circle;
    circle.m_radius = milli(b.radius);
    circle.m_p.Set(milli(b.cx), milli(b.cy));
    b2FixtureDef fixture;
    fixture.shape = b.radius > 0 ? static_cast<const b2Shape*>(&circle) : &box;
    fixture.density =
        b.kind == Kind2D::kDynamic ? milli(b.density > 0 ? b.density : scene.density) : 0.0f;
    fixture.friction = milli(b.friction >= 0 ? b.friction : scene.friction);
    fixture.filter.categoryBits = static_cast<uint16>(b.layer);
    fixture.filter.maskBits = static_cast<uint16>(b.mask);
    fixture.restitution = 0.0f;
    body->CreateFixture(&fixture);
    bodies_.push_back(body);
  }
  for (const RevoluteDesc2D& j : scene.joints) {
    b2RevoluteJointDef def;
    def.Initialize(bodies_[j.a], bodies_[j.b], b2Vec2(milli(j.x), milli(j.y)));
    world_->CreateJoint(&def);
  }
  return true;
}

bool Box2DEngine::add_wave(const Scene2D& scene, uint32_t /*wave*/, std::string& error) {
  error = "box2d: scene " + scene.name + " refused at build";
  return false;
}

void Box2DEngine::step() {
  world_->Step(1.0f / 60.0f, velocity_, position_);
}

Pose2D Box2DEngine::pose(uint32_t index) const {
  const b2Body* body = bodies_[index];
  const b2Vec2 p = body->GetPosition();
  return {p.x, p.y, body->GetAngle()};
}

namespace {

// Box2D's closest-hit callback: clipping the ray at each hit leaves the
// closest one.
class ClosestHit final : public b2RayCastCallback {
 public:
  float ReportFixture(b2Fixture* /*fixture*/, const b2Vec2& /*point*/, const b2Vec2& /*normal*/,
                      float at) override {
    hit = true;
    closest = at;
    return at;
  }
  bool hit = false;
  float closest = 1.0f;
};

}  // namespace

bool Box2DEngine::raycast(double x0, double y0, double x1, double y1, double& fraction) const {
  ClosestHit callback;
  world_->RayCast(&callback, b2Vec2(static_cast<float>(x0), static_cast<float>(y0)),
                  b2Vec2(static_cast<float>(x1), static_cast<float>(y1)));
  if (!callback.hit) return false;
  fraction = callback.closest;
  return true;
}

}  // namespace rwd::bench
