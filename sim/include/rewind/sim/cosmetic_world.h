// SPDX-License-Identifier: MIT
#pragma once
// Render-only physics: a world of cosmetic props (debris, shell casings,
// sparks with a body) that bounce off read-only proxies of an authoritative
// world's bodies, for the eye alone.
//
// The cosmetic world is a separate World3D beside the authoritative one.
// sync() reads the authoritative world and mirrors its bodies as proxies:
// static bodies as static bodies of the same shape, kinematic bodies (and,
// on request, dynamic ones) as kinematic bodies driven to the authoritative
// poses with the velocities that take them there, so a prop is pushed by a
// moving platform or a rolling player as it would be. Props are dynamic
// bodies of the cosmetic world only; nothing here writes to the
// authoritative world, and nothing here is part of its state, its checksum,
// its snapshots, a replay or a message. Two viewers of the same match may
// see different debris: that is the point of a cosmetic layer.
//
// Props live `prop_lifetime_s` and at most `max_props` at once (the oldest
// goes first), so a long match never piles up debris.
#include <cstdint>
#include <memory>
#include <vector>

#include "rewind/core/debug_draw.h"
#include "rewind/core/status.h"
#include "rewind/sim/body.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {

struct CosmeticConfig {
  /// The cosmetic world's own tuning: gravity, tick, substeps. Its tick is
  /// the step step() takes (render frames step it as often as they need).
  WorldConfig world;
  /// Mirror dynamic authoritative bodies too (as kinematic proxies), so
  /// players and crates push debris; static and kinematic ones always are.
  bool proxy_dynamic_bodies = true;
  uint32_t max_props = 256;      ///< at most this many props; adding one more retires the oldest
  float prop_lifetime_s = 8.0f;  ///< a prop is removed this long after it was added (> 0)
};

/// A prop, by its id in the cosmetic world.
struct PropId {
  BodyId body;
  friend bool operator==(const PropId&, const PropId&) = default;
};

class CosmeticWorld {
 public:
  /// A cosmetic world reading geometry from `geometry` (the authoritative
  /// world's store, World3D::shared_geometry(), so proxies of hulls and
  /// meshes share their data). kInvalidArgument for a config
  /// World3D::validate_config refuses, a lifetime not finite and positive,
  /// or max_props 0.
  static Result<std::unique_ptr<CosmeticWorld>> create(const CosmeticConfig& config,
                                                       std::shared_ptr<GeometryStore> geometry);

  /// Mirrors `authority`'s bodies as proxies: new bodies get one, destroyed
  /// or disabled ones lose theirs, moving ones are driven to their present
  /// pose over the cosmetic world's next step. Reads `authority` only.
  /// `authority` must read its geometry from the store given to create().
  void sync(const World3D& authority);
  /// Forgets every proxy's motion, so the next sync() places proxies where
  /// the authority is without a velocity (after a seek or a rollback, when
  /// the authoritative world jumped).
  void teleport_next_sync() { teleport_ = true; }

  /// Adds a prop: a dynamic body (`def.kind` must be kDynamic; a mesh or
  /// height field is refused like any dynamic body's). The oldest prop goes
  /// when max_props are alive.
  Result<PropId> add_prop(const BodyDef& def);
  Status remove_prop(PropId prop);
  /// Removes every prop (proxies stay).
  void clear_props();

  /// Advances the cosmetic world one of its ticks (config.world.tick_seconds)
  /// and retires props past their lifetime.
  void step();

  uint32_t prop_count() const { return static_cast<uint32_t>(props_.size()); }
  bool is_prop(PropId prop) const;
  /// The cosmetic world itself, for poses and queries (read only).
  const World3D& world() const { return world_; }

  /// Appends the props (not the proxies) to `out` in `color`, as
  /// debug_draw draws bodies.
  void draw_props(const DebugDrawOptions& options, DrawColor color, DebugDrawBuffers& out) const;

 private:
  CosmeticWorld(const CosmeticConfig& config, std::shared_ptr<GeometryStore> geometry);
  struct Proxy {
    uint32_t authority_index = 0;
    uint32_t authority_generation = 0;
    BodyId body;
    bool moving = false;  ///< kinematic here: driven each sync
  };
  struct Prop {
    BodyId body;
    uint64_t born_step = 0;
  };

  CosmeticConfig config_;
  World3D world_;
  std::vector<Proxy> proxies_;  ///< by authority index, ascending
  std::vector<Prop> props_;     ///< oldest first
  bool teleport_ = true;
};

}  // namespace rwd::sim
