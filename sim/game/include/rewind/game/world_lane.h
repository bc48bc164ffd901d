// SPDX-License-Identifier: MIT
#pragma once
// Lane adapter for a concrete world type. `World` provides: a constructor
// from its config, step(), config(), state(), save(State&), restore(const
// State&), hash(StateHasher&), static hash_state(const State&, StateHasher&),
// dump_fields(), serialize(), deserialize() and perturb_for_drill(); and
// free functions debug_draw(const World&, options, buffers) and
// view_stats(const World&), found by argument-dependent lookup (both
// lanes' are included here). The adapter adds one virtual call per
// operation and nothing per body.
#include <memory>
#include <type_traits>
#include <utility>

#include "rewind/game/lane.h"
#include "rewind/sim/debug_draw3d.h"
#include "rewind/sim2d/debug_draw2d.h"

namespace rwd::game {

namespace lane_detail {
// The world's own free functions, by argument-dependent lookup; inside
// WorldLane its members of the same names would hide them.
template <class World>
void draw_world(const World& world, const rwd::DebugDrawOptions& options,
                rwd::DebugDrawBuffers& out) {
  debug_draw(world, options, out);
}
template <class World>
rwd::WorldViewStats stats_of(const World& world) {
  return view_stats(world);
}
}  // namespace lane_detail

template <class World>
class WorldLane final : public Lane {
 public:
  /// The world's saved state (trivially copyable arrays, a bulk copy).
  using State = std::remove_cvref_t<decltype(std::declval<const World&>().state())>;
  /// The world's tuning.
  using Config = std::remove_cvref_t<decltype(std::declval<const World&>().config())>;

  /// The snapshot this lane makes: the world's State by value.
  struct Snapshot final : LaneSnapshot {
    State state;
    std::unique_ptr<LaneSnapshot> clone() const override {
      return std::make_unique<Snapshot>(*this);
    }
  };

  /// A world built from `config`, which the world's validation accepts.
  explicit WorldLane(const Config& config) : world_(config) {}

  World& world() { return world_; }
  const World& world() const { return world_; }

  void step() override { world_.step(); }
  std::unique_ptr<LaneSnapshot> make_snapshot() const override {
    return std::make_unique<Snapshot>();
  }
  void save(LaneSnapshot& out) const override { world_.save(static_cast<Snapshot&>(out).state); }
  void restore(const LaneSnapshot& in) override {
    world_.restore(static_cast<const Snapshot&>(in).state);
  }
  void hash(rwd::StateHasher& hasher) const override { world_.hash(hasher); }
  void hash_snapshot(const LaneSnapshot& snapshot, rwd::StateHasher& hasher) const override {
    World::hash_state(static_cast<const Snapshot&>(snapshot).state, hasher);
  }
  void dump_fields(std::vector<rwd::BodyField>& out) const override { world_.dump_fields(out); }
  void serialize(std::vector<uint8_t>& out) const override { world_.serialize(out); }
  Status deserialize(std::span<const uint8_t> bytes) override { return world_.deserialize(bytes); }
  void debug_draw(const rwd::DebugDrawOptions& options, rwd::DebugDrawBuffers& out) const override {
    lane_detail::draw_world(world_, options, out);
  }
  rwd::WorldViewStats view_stats() const override { return lane_detail::stats_of(world_); }
  bool perturb_for_drill() override { return world_.perturb_for_drill(); }

 private:
  World world_;
};

/// The world behind `lane` when it is a WorldLane<World>, else nullptr.
template <class World>
World* world_of(Lane& lane) {
  auto* typed = dynamic_cast<WorldLane<World>*>(&lane);
  return typed != nullptr ? &typed->world() : nullptr;
}

template <class World>
const World* world_of(const Lane& lane) {
  const auto* typed = dynamic_cast<const WorldLane<World>*>(&lane);
  return typed != nullptr ? &typed->world() : nullptr;
}

/// The world state inside `snapshot` when a WorldLane<World> made it, else
/// nullptr.
template <class World>
typename WorldLane<World>::State* state_of(LaneSnapshot& snapshot) {
  auto* typed = dynamic_cast<typename WorldLane<World>::Snapshot*>(&snapshot);
  return typed != nullptr ? &typed->state : nullptr;
}

}  // namespace rwd::game
