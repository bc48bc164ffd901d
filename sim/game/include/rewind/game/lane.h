// SPDX-License-Identifier: MIT
#pragma once
// The lane-neutral face of a physics world. A Simulation drives its world
// only through this interface, one virtual call per tick at most, so the
// rollback core, the server, the client SDK and the replay tools host any
// lane (the 3D float world, a 2D fixed-point world) without knowing which.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "rewind/core/body_field.h"
#include "rewind/core/debug_draw.h"
#include "rewind/core/state_hasher.h"
#include "rewind/core/status.h"

namespace rwd::game {

/// A saved world state, owned by the lane that made it. Opaque to everyone
/// else: only the lane type that made it can restore or hash it.
class LaneSnapshot {
 public:
  virtual ~LaneSnapshot() = default;
  /// A deep copy (allocates; rollback reuses snapshots instead).
  virtual std::unique_ptr<LaneSnapshot> clone() const = 0;
};

/// One physics world behind the operations the simulation needs.
class Lane {
 public:
  virtual ~Lane() = default;

  /// Advances the world by one tick.
  virtual void step() = 0;

  /// An empty snapshot for save(); reusing it keeps later saves free of
  /// allocations once its buffers have grown to the world's size.
  virtual std::unique_ptr<LaneSnapshot> make_snapshot() const = 0;
  /// Copies the whole state into `out`, which make_snapshot() of this lane
  /// type made.
  virtual void save(LaneSnapshot& out) const = 0;
  /// Copies `in` (saved by this lane type) back; restore-then-step equals
  /// continuing-to-step bit for bit.
  virtual void restore(const LaneSnapshot& in) = 0;

  /// Feeds the canonical fields of the state to `hasher`.
  virtual void hash(rwd::StateHasher& hasher) const = 0;
  /// hash() of a saved state (made by this lane type), without restoring it.
  virtual void hash_snapshot(const LaneSnapshot& snapshot, rwd::StateHasher& hasher) const = 0;

  /// Every live body's fields in ascending body index order; `out` is
  /// cleared first.
  virtual void dump_fields(std::vector<rwd::BodyField>& out) const = 0;

  /// Portable encoding of the whole state (resync snapshots); `out` is
  /// replaced.
  virtual void serialize(std::vector<uint8_t>& out) const = 0;
  /// Replaces the state from serialize()'s bytes; kCorrupt leaves it intact.
  virtual Status deserialize(std::span<const uint8_t> bytes) = 0;

  /// Appends the world's debug draw to `out` (rewind/core/debug_draw.h):
  /// for viewers, never part of the state.
  virtual void debug_draw(const rwd::DebugDrawOptions& options,
                          rwd::DebugDrawBuffers& out) const = 0;
  /// The world's counts for a viewer (bodies, awake, contacts, joints).
  virtual rwd::WorldViewStats view_stats() const = 0;

  /// Test hook for desync drills: changes the state slightly, the way a
  /// real non-determinism would, and the same way for the same state.
  /// Returns false, changing nothing, when the world has nothing to change.
  virtual bool perturb_for_drill() = 0;
};

}  // namespace rwd::game
