// SPDX-License-Identifier: MIT
#pragma once
// The joust arena's layout and tuning, shared by its construction
// (joust_build.cpp) and its rules (joust_game.cpp).
#include <array>
#include <cstdint>

#include "rewind/core/det_math.h"
#include "rewind/game/joust_game.h"
#include "rewind/sim/world3d.h"

namespace rwd::game::joust_detail {

// --- the arena ---------------------------------------------------------------
// A square height field of 1 m cells centred on the origin: flat (with low
// bumps) out to kFlatHalf, then a bowl rim rising to the walls.
inline constexpr int32_t kFieldHalfCells = 24;
inline constexpr uint32_t kFieldSamples = 2 * kFieldHalfCells + 1;
inline constexpr int32_t kFlatHalf = 16;   // m: where the rim starts rising
inline constexpr float kRimCurve = 0.05f;  // m of rim per m^2 beyond kFlatHalf
inline constexpr float kBumpHeight = 0.18f;
inline constexpr float kWallHeight = 8.0f;
inline constexpr float kKillPlaneY = -10.0f;
inline constexpr float kWorldHalf = 200.0f;
inline constexpr float kSpawnRadius = 10.0f;

// --- the cars ----------------------------------------------------------------
// A 900 kg box chassis facing +z (+x is the car's left) on four raycast
// wheels; with its lance and rider it weighs about a tonne.
inline constexpr sim::Vec3 kChassisHalf{0.9f, 0.3f, 1.8f};
inline constexpr float kChassisMass = 900.0f;
inline constexpr float kWheelX = 0.8f;
inline constexpr float kWheelZ = 1.2f;
inline constexpr float kWheelAttachY = -0.2f;
inline constexpr float kRestLength = 0.4f;
inline constexpr float kMaxTravel = 0.3f;
inline constexpr float kWheelRadius = 0.35f;
// A 1.6 Hz ride for a quarter of a tonne per wheel, damping ratio 0.4.
inline constexpr float kStiffness = 26000.0f;
inline constexpr float kDamping = 2100.0f;
inline constexpr float kTireFriction = 1.1f;
// The stick sets a speed (full deflection: kTopSpeedMps ahead or behind);
// the drive pushes toward it with up to kDriveForce, at full force from
// kSpeedBandMps away.
inline constexpr float kDriveForce = 6500.0f;  // N
inline constexpr float kTopSpeedMps = 12.0f;
inline constexpr float kSpeedBandMps = 3.0f;
inline constexpr float kChargeFactor = 2.2f;        // drive force multiplier while charging
inline constexpr float kChargeTopSpeedMps = 18.0f;  // top speed while charging
inline constexpr float kBrakeForce = 14000.0f;
inline constexpr float kMaxSteer = 0.6f;          // rad at a standstill
inline constexpr float kSteerFalloffMps = 20.0f;  // steering halves at this speed
inline constexpr int32_t kChargeTicks = 60;
inline constexpr int32_t kChargeCooldownTicks = 240;
// A car this far over (its up axis below this height) for kUpsetTicks is
// put back at its spawn point.
inline constexpr float kUpsetUpY = 0.3f;
inline constexpr int32_t kUpsetTicks = 120;

// The lance: a 4 m pole on the car's left at a rider's chest height,
// welded at its back end, its tip 2.8 m ahead of the bumper.
inline constexpr sim::Vec3 kLanceHalf{0.06f, 0.06f, 2.0f};
inline constexpr sim::Vec3 kLanceCentre{0.55f, 0.85f, 2.6f};
inline constexpr float kLanceDensity = 500.0f;

// The rider: the engine's ragdoll (ragdoll3d.h), 1.8 m and 70 kg, sitting
// on the roof behind the lance's foot with its legs out along the car and
// its forearms forward. kSeat is the pelvis centre in the chassis frame:
// the legs, level with the hips, just clear the roof.
inline constexpr float kRiderHeight = 1.8f;
inline constexpr float kRiderMass = 70.0f;
inline constexpr sim::Vec3 kSeat{0.0f, 0.44f, -0.4f};
// The seat weld lets go when one tick's reaction exceeds this (N s, or
// N m s for its turning part): a crash, a roll, a lance or the ball. Riding
// over the bumps and cornering hard load it well below.
inline constexpr float kSeatBreakImpulse = 150.0f;
// A lance striking a rider with at least this normal impulse in one tick
// throws the rider off whatever the weld says, and flings it.
inline constexpr float kUnseatImpulse = 40.0f;
inline constexpr float kThrowSpeed = 4.0f;  // m/s along the striking lance
inline constexpr float kThrowLift = 2.5f;   // m/s up
inline constexpr int32_t kHitMemoryTicks = 45;
// A rider thrown with no strike remembered scores for the first opponent
// lance to touch it within this many ticks.
inline constexpr int32_t kCreditTicks = 6;
inline constexpr int32_t kRespawnTicks = 180;

// --- the wrecking ball -------------------------------------------------------
// A static gantry (two posts and a beam along x) over the centre; a chain
// of capsule links on ball joints, the ball at its end, released 50 degrees
// out in the y-z plane.
inline constexpr float kPivotY = 6.8f;
inline constexpr float kPostX = 4.5f;
inline constexpr float kLinkLength = 0.6f;  // cap to cap
inline constexpr float kLinkRadius = 0.09f;
inline constexpr float kLinkDensity = 3000.0f;
inline constexpr float kBallRadius = 0.7f;
inline constexpr float kBallDensity = 1500.0f;
inline constexpr float kReleaseAngle = 50.0f * rwd::kPi / 180.0f;
// Near the bottom of its swing the ball gets a small push along its motion
// while slower than this, so it keeps swinging all match.
inline constexpr float kPumpSpeedMps = 5.5f;
inline constexpr float kPumpDeltaMps = 0.05f;
inline constexpr float kPumpZone = 0.6f;  // m either side of the gantry

inline constexpr uint32_t kLayerGround = 1u << 0;
inline constexpr uint32_t kLayerCar = 1u << 1;
inline constexpr uint32_t kLayerChain = 1u << 3;
// Each rider's parts are on one of the top 24 bits (player p on bit
// 8 + p % 24) and skip only their own bit: a figure's parts never collide
// with each other, and riders collide with each other's (but for players
// 24 slots apart, whose riders share a bit and pass through each other).
inline constexpr uint32_t kRiderLayerFirst = 8;
inline constexpr uint32_t kRiderLayerCount = 24;
inline constexpr uint32_t kLayerRiders = 0xFFFFFF00u;
inline constexpr uint64_t kTagChassis = 0x100;
inline constexpr uint64_t kTagLance = 0x200;
inline constexpr uint64_t kTagRider = 0x1000;  // + player * 16 + part
inline constexpr uint64_t kTagChain = 0x800;
inline constexpr uint64_t kTagBall = 0x900;

// Where player p's car starts and comes back: on a circle, facing the
// centre, dropped just onto the ground.
void spawn_pose(const sim::World3D& world, uint32_t player, uint32_t player_count,
                sim::Vec3& position, sim::Quat& rotation);

// Player p's rider tensed (seated) or limp (thrown).
void set_rider_tone(sim::World3D& world, const JoustState& state, uint32_t p, bool on);

}  // namespace rwd::game::joust_detail
