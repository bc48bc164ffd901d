// SPDX-License-Identifier: MIT
// The shared sedan (rewind/scenes/vehicle_scene.h) driven on Rewind's
// update_vehicle and on Bullet's btRaycastVehicle, in one process, one
// thread, on flat ground: the time from rest to 20 m/s under a constant
// drive force below the grip, the braking distance from 20 m/s under a
// brake force below and beyond the grip, and the wall time per tick
// (vehicle update plus world step), each beside its analytic answer.
//
// How the car becomes a btRaycastVehicle (same mass, box, wheel geometry,
// springs and friction):
// - Bullet's suspension stiffness and damping are per kilogram of chassis
//   (it multiplies the spring force by the chassis mass), so they are k / m
//   and c / m, compression and relaxation alike; max travel in cm; the
//   default 6000 N force cap on a spring is lifted;
// - friction slip is the tire's mu (1.0; Bullet does not read the ground's
//   friction, Rewind takes the geometric mean with the ground's 1.0);
// - roll influence 1 (Bullet's default 0.1 moves the side force's point up
//   toward the centre of mass; it does not act in a straight line);
// - drive: applyEngineForce(F / 4) on each wheel; brake: Bullet's brake is
//   the largest impulse per step the wheel may use to stop its rolling, so
//   a brake force B becomes setBrake(B / 4 * dt);
// - Bullet's friction circle weighs the longitudinal impulse at half
//   (so a straight-line tire takes up to 2 mu N) and is only enforced on
//   wheels with a sideways impulse; the braking-beyond-grip row shows it;
// - the world steps once per tick of 1/60 s (Bullet's default solver, 10
//   iterations), Rewind at its defaults (4 substeps).
// Not a test: a program that prints a table. Run it from the bench preset.
#include <BulletDynamics/Vehicle/btRaycastVehicle.h>
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "rewind/scenes/vehicle_scene.h"
#include "rewind/sim/vehicle3d.h"
#include "rewind/sim/world3d.h"

namespace rwd::bench {
namespace {

using scenes::CarSpec;

constexpr float kDt = 1.0f / 60.0f;
constexpr float kG = 9.81f;
constexpr int kSettleTicks = 120;
constexpr int kMaxTicks = 60 * 60;

/// One car on one engine, driven tick by tick.
class Car {
 public:
  virtual ~Car() = default;
  /// Sets this tick's drive and brake forces (N, whole car) and steps.
  virtual void step(float drive_n, float brake_n) = 0;
  virtual float forward_speed() const = 0;  ///< m/s along +z
  virtual float forward_position() const = 0;
  virtual void set_forward_speed(float mps) = 0;
};

class RewindVehicle final : public Car {
 public:
  explicit RewindVehicle(const CarSpec& spec) {
    sim::BodyDef ground;
    ground.kind = sim::BodyKind::kStatic;
    ground.shape = sim::Shape::make_box({50.0f, 0.5f, 1000.0f});
    ground.position = {0.0f, -0.5f, 900.0f};
    ground.material.friction = 1.0f;
    (void)world_.create_body(ground);
    car_ = scenes::add_car(world_, spec, {0.0f, spec.ride_height_m(kG) + 0.05f, 0.0f});
  }
  void step(float drive_n, float brake_n) override {
    car_.max_drive_force_n = drive_n;
    car_.max_brake_force_n = brake_n;
    sim::VehicleControls3D controls;
    controls.throttle = drive_n > 0.0f ? 1.0f : 0.0f;
    controls.brake = brake_n > 0.0f ? 1.0f : 0.0f;
    if (!car_.drive(world_, controls).ok()) std::printf("update_vehicle refused\n");
    world_.step();
  }
  float forward_speed() const override { return world_.linear_velocity(car_.chassis).z; }
  float forward_position() const override { return world_.position(car_.chassis).z; }
  void set_forward_speed(float mps) override {
    (void)world_.set_linear_velocity(car_.chassis, {0.0f, 0.0f, mps});
  }

 private:
  sim::World3D world_;
  scenes::RewindCar car_;
};

class BulletVehicle final : public Car {
 public:
  explicit BulletVehicle(const CarSpec& spec)
      : dispatcher_(&collision_config_),
        world_(&dispatcher_, &broadphase_, &solver_, &collision_config_),
        ground_shape_(btVector3(50.0f, 0.5f, 1000.0f)),
        chassis_shape_(btVector3(spec.half_extents.x, spec.half_extents.y, spec.half_extents.z)),
        raycaster_(&world_) {
    world_.setGravity(btVector3(0.0f, -kG, 0.0f));

    btRigidBody::btRigidBodyConstructionInfo ground_info(0.0f, nullptr, &ground_shape_);
    ground_info.m_startWorldTransform.setOrigin(btVector3(0.0f, -0.5f, 900.0f));
    ground_info.m_friction = 1.0f;
    ground_ = std::make_unique<btRigidBody>(ground_info);
    world_.addRigidBody(ground_.get());

    btVector3 inertia;
    chassis_shape_.calculateLocalInertia(spec.mass_kg, inertia);
    btRigidBody::btRigidBodyConstructionInfo chassis_info(spec.mass_kg, nullptr, &chassis_shape_,
                                                          inertia);
    chassis_info.m_startWorldTransform.setOrigin(
        btVector3(0.0f, spec.ride_height_m(kG) + 0.05f, 0.0f));
    chassis_ = std::make_unique<btRigidBody>(chassis_info);
    chassis_->setActivationState(DISABLE_DEACTIVATION);
    world_.addRigidBody(chassis_.get());

    btRaycastVehicle::btVehicleTuning tuning;
    tuning.m_suspensionStiffness = spec.stiffness_npm / spec.mass_kg;
    tuning.m_suspensionCompression = spec.damping_nspm / spec.mass_kg;
    tuning.m_suspensionDamping = spec.damping_nspm / spec.mass_kg;
    tuning.m_maxSuspensionTravelCm = spec.max_travel_m * 100.0f;
    tuning.m_frictionSlip = spec.friction;
    tuning.m_maxSuspensionForce = 1e7f;
    vehicle_ = std::make_unique<btRaycastVehicle>(tuning, chassis_.get(), &raycaster_);
    vehicle_->setCoordinateSystem(0, 1, 2);  // right x, up y, forward z
    for (int i = 0; i < 4; ++i) {
      const sim::Vec3 a = spec.attachment(i);
      btWheelInfo& wheel = vehicle_->addWheel(
          btVector3(a.x, a.y, a.z), btVector3(0.0f, -1.0f, 0.0f), btVector3(-1.0f, 0.0f, 0.0f),
          spec.rest_length_m, spec.radius_m, tuning, i < 2);
      wheel.m_rollInfluence = 1.0f;
    }
    world_.addVehicle(vehicle_.get());
  }
  ~BulletVehicle() override {
    world_.removeVehicle(vehicle_.get());
    world_.removeRigidBody(chassis_.get());
    world_.removeRigidBody(ground_.get());
  }
  void step(float drive_n, float brake_n) override {
    for (int i = 0; i < 4; ++i) {
      vehicle_->applyEngineForce(drive_n / 4.0f, i);
      vehicle_->setBrake(brake_n / 4.0f * kDt, i);
    }
    world_.stepSimulation(kDt, 1, kDt);
  }
  float forward_speed() const override { return chassis_->getLinearVelocity().z(); }
  float forward_position() const override { return chassis_->getCenterOfMassPosition().z(); }
  void set_forward_speed(float mps) override {
    chassis_->setLinearVelocity(btVector3(0.0f, 0.0f, mps));
  }

 private:
  btDefaultCollisionConfiguration collision_config_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_;
  btBoxShape ground_shape_;
  btBoxShape chassis_shape_;
  btDefaultVehicleRaycaster raycaster_;
  std::unique_ptr<btRigidBody> ground_;
  std::unique_ptr<btRigidBody> chassis_;
  std::unique_ptr<btRaycastVehicle> vehicle_;
};

/// Wall time of every tick stepped through timed().
struct Clock {
  double seconds = 0.0;
  long ticks = 0;
  template <class F>
  void timed(F&& f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++ticks;
  }
};

template <class Make>
double time_to_20(Make make, float drive_n, Clock& clock) {
  auto car = make();
  for (int t = 0; t < kSettleTicks; ++t) clock.timed([&] { car->step(0.0f, 0.0f); });
  for (int t = 1; t <= kMaxTicks; ++t) {
    clock.timed([&] { car->step(drive_n, 0.0f); });
    if (car->forward_speed() >= 20.0f) return t * static_cast<double>(kDt);
  }
  return NAN;
}

template <class Make>
double braking_distance(Make make, float brake_n, Clock& clock) {
  auto car = make();
  for (int t = 0; t < kSettleTicks; ++t) clock.timed([&] { car->step(0.0f, 0.0f); });
  car->set_forward_speed(20.0f);
  const double z0 = car->forward_position();
  for (int t = 0; t < kMaxTicks && car->forward_speed() > 1e-3f; ++t) {
    clock.timed([&] { car->step(0.0f, brake_n); });
  }
  return car->forward_position() - z0;
}

}  // namespace
}  // namespace rwd::bench

int main() {
  using namespace rwd::bench;  // NOLINT: a small program
  const CarSpec spec;
  const auto rewind = [&] { return std::make_unique<RewindVehicle>(spec); };
  const auto bullet = [&] { return std::make_unique<BulletVehicle>(spec); };
  const float drive_n = 6000.0f;  // half the grip (mu m g = 11,772 N)
  // Light enough that no wheel reaches its grip even with the load the
  // braking moves to the front (m a h / wheelbase): the analytic answer
  // v^2 / (2 B / m) holds. (At 8000 N the unloaded rear wheels lock.)
  const float gentle_brake_n = 5000.0f;
  const float hard_brake_n = 40000.0f;  // 3.4 times the grip
  const double m = spec.mass_kg;
  const double mu_g = spec.friction * kG;

  Clock rewind_clock;
  Clock bullet_clock;
  const double r_accel = time_to_20(rewind, drive_n, rewind_clock);
  const double b_accel = time_to_20(bullet, drive_n, bullet_clock);
  const double r_gentle = braking_distance(rewind, gentle_brake_n, rewind_clock);
  const double b_gentle = braking_distance(bullet, gentle_brake_n, bullet_clock);
  const double r_hard = braking_distance(rewind, hard_brake_n, rewind_clock);
  const double b_hard = braking_distance(bullet, hard_brake_n, bullet_clock);

  std::printf("Sedan: %.0f kg, k %.0f N/m, c %.0f N s/m, mu %.1f, 60 Hz\n", spec.mass_kg,
              spec.stiffness_npm, spec.damping_nspm, spec.friction);
  std::printf("%-40s %10s %10s %10s\n", "", "Rewind", "Bullet", "analytic");
  std::printf("%-40s %10.3f %10.3f %10.3f\n", "0 to 20 m/s, 6000 N drive (s)", r_accel, b_accel,
              20.0 / (drive_n / m));
  std::printf("%-40s %10.2f %10.2f %10.2f\n", "20 m/s to rest, 5000 N brake (m)", r_gentle,
              b_gentle, 400.0 / (2.0 * gentle_brake_n / m));
  std::printf("%-40s %10.2f %10.2f %10.2f\n", "20 m/s to rest, 40000 N brake (m)", r_hard, b_hard,
              400.0 / (2.0 * mu_g));
  std::printf("%-40s %10.4f %10.4f\n", "ms per tick (update + step)",
              1e3 * rewind_clock.seconds / static_cast<double>(rewind_clock.ticks),
              1e3 * bullet_clock.seconds / static_cast<double>(bullet_clock.ticks));
  return 0;
}
