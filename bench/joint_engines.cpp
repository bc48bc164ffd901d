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

btQuaternion bt(sim::Quat q) {
  return {q.x, q.y, q.z, q.w};
}

/// Keeps the bodies of one collision group (JointSceneBody::collision_group,
/// held in each body's user index) from colliding, after Bullet's own
/// group and mask test: the pair cache never sees them, as Rewind's
/// broadphase never sees bodies whose layers and masks disagree.
class GroupFilter final : public btOverlapFilterCallback {
 public:
  bool needBroadphaseCollision(btBroadphaseProxy* p0, btBroadphaseProxy* p1) const override {
    if ((p0->m_collisionFilterGroup & p1->m_collisionFilterMask) == 0 ||
        (p1->m_collisionFilterGroup & p0->m_collisionFilterMask) == 0) {
      return false;
    }
    const int g0 = static_cast<const btCollisionObject*>(p0->m_clientObject)->getUserIndex();
    const int g1 = static_cast<const btCollisionObject*>(p1->m_clientObject)->getUserIndex();
    return g0 < 0 || g0 != g1;
  }
};

/// A limited joint's frames on each side, the way Rewind makes them
/// (World3D::create_joint): at the starting poses, A's frame has its
/// `along` axis on axis_a, and B's is that frame swung by the shortest arc
/// onto axis_b, so every angle counts from the starting pose (and the
/// frames' turn about that axis, which differs from Rewind's, changes no
/// angle). Side a of -1 is the world.
void joint_frames(const scenes::JointScene& scene, const scenes::JointSceneJoint& j,
                  const btVector3& along, btTransform& frame_a, btTransform& frame_b) {
  auto turn = [&](int body) {
    if (body < 0) return btQuaternion::getIdentity();
    return bt(scene.bodies[static_cast<size_t>(body)].rotation);
  };
  const btQuaternion rot_a = turn(j.a), rot_b = turn(j.b);
  const btVector3 axis_a = quatRotate(rot_a, bt(j.axis_a)).normalized();
  const btVector3 axis_b = quatRotate(rot_b, bt(j.axis_b)).normalized();
  const btQuaternion world_a = shortestArcQuat(along, axis_a);
  const btQuaternion world_b = shortestArcQuat(axis_a, axis_b) * world_a;
  frame_a = btTransform(rot_a.inverse() * world_a, bt(j.local_a));
  frame_b = btTransform(rot_b.inverse() * world_b, bt(j.local_b));
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
    world_->getPairCache()->setOverlapFilterCallback(&filter_);
    for (const scenes::JointSceneBody& b : scene.bodies) {
      std::unique_ptr<btCollisionShape> shape;
      switch (b.shape) {
        case scenes::JointSceneShape::kSphere:
          shape = std::make_unique<btSphereShape>(b.half.x);
          break;
        case scenes::JointSceneShape::kBox:
          shape = std::make_unique<btBoxShape>(bt(b.half));
          break;
        case scenes::JointSceneShape::kCapsule:
          // Along local y, like Rewind's; Bullet's height is between the
          // cap centres.
          shape = std::make_unique<btCapsuleShape>(b.half.x, 2.0f * b.half_height);
          break;
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
      body->setUserIndex(b.collision_group);
      world_->addRigidBody(body.get());
      shapes_.push_back(std::move(shape));
      bodies_.push_back(std::move(body));
    }
    for (const scenes::JointSceneJoint& j : scene.joints) {
      btRigidBody& b = *bodies_[static_cast<size_t>(j.b)];
      std::unique_ptr<btTypedConstraint> c;
      if (j.limited) {
        c = limited_joint(scene, j);
      } else if (j.type == scenes::JointSceneType::kBall) {
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
  /// A joint with limits, on frames made as Rewind makes them
  /// (joint_frames()). A ball joint becomes a btConeTwistConstraint (its
  /// x axis the twist axis, both swing spans the cone's half angle), a
  /// hinge a btHingeConstraint on frames (its z axis the hinge); both keep
  /// Bullet's default limit softness, bias and relaxation.
  std::unique_ptr<btTypedConstraint> limited_joint(const scenes::JointScene& scene,
                                                   const scenes::JointSceneJoint& j) {
    // A joint to the world joins Bullet's fixed body, whose frame is the
    // world's, so A stays side a (the one-body constructors make the body
    // side A instead).
    btRigidBody& a =
        j.a < 0 ? btTypedConstraint::getFixedBody() : *bodies_[static_cast<size_t>(j.a)];
    btRigidBody& b = *bodies_[static_cast<size_t>(j.b)];
    btTransform fa, fb;
    if (j.type == scenes::JointSceneType::kBall) {
      joint_frames(scene, j, {1, 0, 0}, fa, fb);
      // Bullet's twist limit is symmetric, +-span about the frames' zero;
      // Rewind's any range. Both split the relative turn into a swing
      // then a twist t about x, so turning B's frame by -centre about x
      // leaves the swing and makes Bullet's twist t - centre: within
      // +-span exactly when t is within [twist_lower, twist_upper]. (The
      // ragdoll's ranges are symmetric: centre 0.)
      const float centre = 0.5f * (j.twist_lower + j.twist_upper);
      const float span = 0.5f * (j.twist_upper - j.twist_lower);
      fb.setRotation(fb.getRotation() * btQuaternion(btVector3(1, 0, 0), -centre));
      auto c = std::make_unique<btConeTwistConstraint>(a, b, fa, fb);
      c->setLimit(j.cone_angle, j.cone_angle, span);
      return c;
    }
    joint_frames(scene, j, {0, 0, 1}, fa, fb);
    auto h = std::make_unique<btHingeConstraint>(a, b, fa, fb);
    // Bullet's hinge angle on frames counts B turning about the axis
    // negative (getHingeAngle() is -0.3 for B turned +0.3 about z, checked
    // on 3.24): Rewind's [lower, upper] is Bullet's [-upper, -lower].
    h->setLimit(-j.upper, -j.lower);
    if (j.friction_torque_nm > 0.0f) {
      h->enableAngularMotor(true, 0.0f, j.friction_torque_nm * kTick);
    }
    return h;
  }

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
  GroupFilter filter_;
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
