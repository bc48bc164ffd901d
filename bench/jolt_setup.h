// SPDX-License-Identifier: MIT
#pragma once
// What every Jolt world of bench/ needs: Jolt's process-wide set-up, and two
// object layers (static and moving) with the filters between them. Includes
// Jolt: for bench/jolt_*.cpp only.
#include <Jolt/Jolt.h>

#include <Jolt/Core/Factory.h>
#include <Jolt/Physics/Collision/BroadPhase/BroadPhaseLayer.h>
#include <Jolt/Physics/Collision/ObjectLayer.h>
#include <Jolt/RegisterTypes.h>

#include <mutex>

namespace rwd::bench::jolt_setup {

/// Jolt's allocator hooks, factory and collision dispatch tables, once per
/// process (inline: one instance across the files that use it).
inline void init_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    JPH::RegisterDefaultAllocator();
    JPH::Factory::sInstance = new JPH::Factory();
    JPH::RegisterTypes();
  });
}

// Static bodies never test against each other.
constexpr JPH::ObjectLayer kStaticLayer = 0;
constexpr JPH::ObjectLayer kMovingLayer = 1;
inline const JPH::BroadPhaseLayer kStaticBroadPhase(0);
inline const JPH::BroadPhaseLayer kMovingBroadPhase(1);

class BroadPhaseLayers final : public JPH::BroadPhaseLayerInterface {
 public:
  JPH::uint GetNumBroadPhaseLayers() const override { return 2; }
  JPH::BroadPhaseLayer GetBroadPhaseLayer(JPH::ObjectLayer layer) const override {
    return layer == kStaticLayer ? kStaticBroadPhase : kMovingBroadPhase;
  }
#if defined(JPH_EXTERNAL_PROFILE) || defined(JPH_PROFILE_ENABLED)
  const char* GetBroadPhaseLayerName(JPH::BroadPhaseLayer layer) const override {
    return layer == kStaticBroadPhase ? "static" : "moving";
  }
#endif
};

class ObjectVsBroadPhase final : public JPH::ObjectVsBroadPhaseLayerFilter {
 public:
  bool ShouldCollide(JPH::ObjectLayer object, JPH::BroadPhaseLayer broad) const override {
    return object == kMovingLayer || broad == kMovingBroadPhase;
  }
};

class ObjectPairs final : public JPH::ObjectLayerPairFilter {
 public:
  bool ShouldCollide(JPH::ObjectLayer a, JPH::ObjectLayer b) const override {
    return a == kMovingLayer || b == kMovingLayer;
  }
};

}  // namespace rwd::bench::jolt_setup
