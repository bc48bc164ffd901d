// SPDX-License-Identifier: MIT
#include "joint_engines.h"

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <string>
#include <vector>

namespace rwd::bench {
namespace {

constexpr float kTick = 1.0f / 60.0f;

class RewindJoints final : public JointEngine {
 public:
  explicit RewindJoints(int substeps) : substeps_(substeps) {}
  std::string name() const override { return "rewind"; }
  std::string settings() const override { return "substeps=" + std::to_string(substeps_); }
  bool is_default() const override { return substeps_ == sim::WorldConfig{}.substeps; }
  bool build(const scenes::JointScene& scene, std::string& error) override {
    sim::WorldConfig config;
    config.gravity = scene.gravity;
    config.tick_seconds = kTick;
    config.substeps = substeps_;
    config.enable_sleep = false;
    world_ = std::make_unique<sim::World3D>(config);
    built_ = scenes::build_rewind(*world_, scene);
    error = built_.error;
    return error.empty();
  }
  void step() override { world_->step(); }
  void states(std::vector<scenes::JointBodyState>& out) const override {
    built_.states(*world_, out);
  }

 private:
  int substeps_;
  std::unique_ptr<sim::World3D> world_;
  scenes::RewindJointScene built_;
};

btVector3 bt(sim::Vec3 v) {
  return {v.x, v.y, v.z};
}

class BulletJoints final : public JointEngine {
 public:
  explicit BulletJoints(int iterations) : iterations_(iterations) {}
  ~BulletJoints() override { clear(); }
  std::string name() const override { return "bullet"; }
  std::string settings() const override { return "iterations=" + std::to_string(iterations_); }
  bool is_default() const override { return iterations_ == 10; }

  bool build(const scenes::JointScene& scene, std::string& error) override {
    clear();
    config_ = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
    world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                       solver_.get(), config_.get());
    world_->setGravity(bt(scene.gravity));
    world_->getSolverInfo().m_numIterations = iterations_;
    for (const scenes::JointSceneBody& b : scene.bodies) {
      std::unique_ptr<btCollisionShape> shape;
      if (b.shape == scenes::JointSceneShape::kSphere) {
        shape = std::make_unique<btSphereShape>(b.half.x);
      } else {
        shape = std::make_unique<btBoxShape>(bt(b.half));
      }
      const float mass = b.mass_kg();
      btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape.get(),
                                                    b.fixed ? btVector3(0, 0, 0) : bt(b.inertia()));
      info.m_startWorldTransform.setOrigin(bt(b.position));
      info.m_startWorldTransform.setRotation(
          btQuaternion(b.rotation.x, b.rotation.y, b.rotation.z, b.rotation.w));
      info.m_friction = b.friction;
      info.m_angularDamping = b.angular_damping;
      auto body = std::make_unique<btRigidBody>(info);
      if (!b.fixed) body->setActivationState(DISABLE_DEACTIVATION);
      world_->addRigidBody(body.get());
      shapes_.push_back(std::move(shape));
      bodies_.push_back(std::move(body));
    }
    for (const scenes::JointSceneJoint& j : scene.joints) {
      btRigidBody& b = *bodies_[static_cast<size_t>(j.b)];
      std::unique_ptr<btTypedConstraint> c;
      if (j.type == scenes::JointSceneType::kBall) {
        if (j.a < 0) {
          c = std::make_unique<btPoint2PointConstraint>(b, bt(j.local_b));
        } else {
          c = std::make_unique<btPoint2PointConstraint>(*bodies_[static_cast<size_t>(j.a)], b,
                                                        bt(j.local_a), bt(j.local_b));
        }
      } else {
        std::unique_ptr<btHingeConstraint> h;
        if (j.a < 0) {
          h = std::make_unique<btHingeConstraint>(b, bt(j.local_b), bt(j.axis_b));
        } else {
          h = std::make_unique<btHingeConstraint>(*bodies_[static_cast<size_t>(j.a)], b,
                                                  bt(j.local_a), bt(j.local_b), bt(j.axis_a),
                                                  bt(j.axis_b));
        }
        if (j.friction_torque_nm > 0.0f) {
          h->enableAngularMotor(true, 0.0f, j.friction_torque_nm * kTick);
        }
        c = std::move(h);
      }
      if (!c) {
        error = "bullet: a joint it cannot build";
        return false;
      }
      world_->addConstraint(c.get(), true);
      constraints_.push_back(std::move(c));
    }
    return true;
  }

  void step() override { world_->stepSimulation(kTick, 1, kTick); }

  void states(std::vector<scenes::JointBodyState>& out) const override {
    out.resize(bodies_.size());
    for (size_t i = 0; i < bodies_.size(); ++i) {
      const btRigidBody& b = *bodies_[i];
      const btTransform& t = b.getWorldTransform();
      const btQuaternion q = t.getRotation();
      const btVector3 p = t.getOrigin();
      const btVector3 v = b.getLinearVelocity();
      const btVector3 w = b.getAngularVelocity();
      out[i] = {{p.x(), p.y(), p.z()},
                {q.x(), q.y(), q.z(), q.w()},
                {v.x(), v.y(), v.z()},
                {w.x(), w.y(), w.z()}};
    }
  }

 private:
  void clear() {
    if (world_) {
      for (auto& c : constraints_) world_->removeConstraint(c.get());
      for (auto& b : bodies_) world_->removeRigidBody(b.get());
    }
    constraints_.clear();
    bodies_.clear();
    shapes_.clear();
    world_.reset();
    solver_.reset();
    broadphase_.reset();
    dispatcher_.reset();
    config_.reset();
  }

  int iterations_;
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<std::unique_ptr<btTypedConstraint>> constraints_;
};

}  // namespace

std::unique_ptr<JointEngine> make_rewind_joint_engine(int substeps) {
  return std::make_unique<RewindJoints>(substeps);
}

std::unique_ptr<JointEngine> make_bullet_joint_engine(int iterations) {
  return std::make_unique<BulletJoints>(iterations);
}

}  // namespace rwd::bench
