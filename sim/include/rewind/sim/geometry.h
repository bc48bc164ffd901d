// SPDX-License-Identifier: MIT
#pragma once
// Shared, immutable collision geometry: convex hulls today, triangle meshes,
// height fields and compounds as they come. A game registers each piece
// once (typically while loading a level), gets a GeometryId, and refers to
// it from any number of bodies through Shape::make_hull(id). World state
// holds only the id, so snapshots stay small and flat and never copy level
// geometry; each entry is hashed once at registration, and a snapshot
// names the digest of the geometry it was taken with so a world that holds
// different geometry refuses it.
//
// Entries are never removed or changed, so a state saved earlier always
// refers to geometry that still exists. A store may be shared by several
// worlds (a server's match and its replay verifier, say) through
// std::shared_ptr; it is not thread-safe for adding while another thread
// steps a world that reads it.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "rewind/sim/geometry_id.h"
#include "rewind/sim/math.h"
#include "rewind/sim/status.h"

namespace rwd::sim {

namespace d3 {
struct Hull;
}

enum class GeometryKind : uint8_t {
  kHull = 0,  ///< a convex hull of 4 to 64 vertices
};

/// What a registered hull turned out to be.
struct HullInfo {
  uint32_t vertex_count = 0;
  uint32_t face_count = 0;  ///< polygon faces (coplanar triangles merged)
  uint32_t edge_count = 0;
  float volume = 0.0f;  ///< m^3
  /// Centre of mass in the frame the points were given in (uniform
  /// density). A hull body turns about this point; its position (what
  /// World3D::position reports and set_transform takes) stays the origin of
  /// the frame the points were given in.
  Vec3 center_of_mass;
  /// The principal axes of inertia in the same frame: the hull's mass frame
  /// is this rotation about center_of_mass.
  Quat principal_axes;
  /// Principal moments of inertia per kilogram about those axes, m^2.
  Vec3 unit_inertia;
};

class GeometryStore {
 public:
  /// At most this many entries per store.
  static constexpr uint32_t kMaxEntries = 1u << 16;

  GeometryStore();
  ~GeometryStore();
  GeometryStore(const GeometryStore&) = delete;
  GeometryStore& operator=(const GeometryStore&) = delete;

  /// Registers the convex hull whose corners are exactly `points` (metres,
  /// in the body's frame; 4 to 64 of them, each within 1000 m of the
  /// origin). Refused with kInvalidArgument and a message naming the
  /// problem: a non-finite or out-of-range coordinate, duplicate points,
  /// all points on a line or a plane (no volume), or a point that is not a
  /// corner (inside the hull, or on one of its faces or edges). Points are
  /// first snapped to the canonical grid (quantize()), like every value
  /// that enters the simulation. Registering the same points again returns
  /// the id they already have.
  Result<GeometryId> add_hull(std::span<const Vec3> points);
  /// Registers the convex hull of a point cloud (4 to 4096 points; the
  /// points inside the hull are dropped). A hull of more than 64 corners is
  /// reduced to 64 of them. Same errors as add_hull() for bad coordinates
  /// and clouds without volume.
  Result<GeometryId> add_hull_from_points(std::span<const Vec3> points);

  /// Number of entries; ids run from 0 to size() - 1.
  uint32_t size() const;
  bool contains(GeometryId id) const;
  /// The kind of an entry, or nullopt for an unknown id.
  std::optional<GeometryKind> kind(GeometryId id) const;
  /// XXH3-64 of an entry's canonical encoding (0 for an unknown id).
  uint64_t hash(GeometryId id) const;
  /// XXH3-64 over the hashes of the first `count` entries (count <= size()),
  /// in id order: what a snapshot records of the geometry it refers to.
  uint64_t digest(uint32_t count) const;

  /// A hull's summary, or nullopt when `id` is not a hull.
  std::optional<HullInfo> hull_info(GeometryId id) const;
  /// A hull's corners in the frame its points were given in (after
  /// snapping), for drawing; `out` is cleared first (empty for a non-hull).
  void hull_vertices(GeometryId id, std::vector<Vec3>& out) const;

  /// The engine's form of a hull (internal), or nullptr when `id` is not a
  /// hull. The pointer stays valid for the store's lifetime.
  const d3::Hull* hull(uint32_t id) const;

 private:
  Result<GeometryId> add(std::unique_ptr<d3::Hull> hull);

  struct Entry;
  std::vector<Entry> entries_;
};

}  // namespace rwd::sim
