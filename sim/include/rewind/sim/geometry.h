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

#include "rewind/core/status.h"
#include "rewind/sim/geometry_id.h"
#include "rewind/sim/math.h"
#include "rewind/sim/shape.h"

namespace rwd::sim {

namespace d3 {
struct Hull;
struct TriangleMesh;
struct HeightField;
struct Compound;
}  // namespace d3

enum class GeometryKind : uint8_t {
  kHull = 0,         ///< a convex hull of 4 to 64 vertices
  kMesh = 1,         ///< a triangle mesh (static or kinematic bodies only)
  kHeightField = 2,  ///< a grid of heights (static or kinematic bodies only)
  kCompound = 3,     ///< a rigid group of convex children
};

/// One child of a compound: a sphere, box, capsule or hull (of the same
/// store), placed by its own authored frame in the compound's frame.
struct CompoundChild {
  Shape shape;
  Vec3 position;  ///< metres, within 1000 m of the compound's origin
  Quat rotation;  ///< normalized when registered
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

  /// Registers a triangle mesh for static and kinematic bodies (a level, a
  /// moving platform): `vertices` (m, in the body's frame; 3 to 2^20, each
  /// within 1e5 m of the origin) and `indices`, three per triangle (1 to
  /// 2^21 triangles), counter-clockwise seen from the front. Vertices shared
  /// by index make shared edges, across which bodies slide without catching
  /// (flat and concave edges give no edge contacts). A one-sided mesh
  /// collides and is hit by rays only from the front. Refused with the
  /// index of the problem: indices out of range, degenerate triangles,
  /// non-finite or out-of-range coordinates. A bounding-volume hierarchy is
  /// built once, here.
  Result<GeometryId> add_mesh(std::span<const Vec3> vertices, std::span<const uint32_t> indices,
                              bool one_sided = false);
  /// Registers a height field for static and kinematic bodies: `rows` x
  /// `cols` samples (2 to 4096 each), row-major in `heights`; sample (r, c)
  /// is at (c * scale.x, heights[r * cols + c] * scale.y, r * scale.z) in
  /// the body's frame, so the surface faces +y. `holes`, empty or one byte
  /// per cell ((rows - 1) x (cols - 1), 1 = no ground there). Two triangles
  /// per cell; bodies slide across cell edges without catching.
  Result<GeometryId> add_height_field(uint32_t rows, uint32_t cols, Vec3 scale,
                                      std::span<const float> heights,
                                      std::span<const uint8_t> holes = {});

  /// Registers a compound of 1 to 16 convex children (spheres, boxes,
  /// capsules, hulls registered before it). Its mass comes from the
  /// children's volumes at the body's density, its centre of mass and
  /// principal inertia from their poses (parallel-axis theorem); a body of
  /// it turns about that centre, while its position is the origin of the
  /// frame the children were placed in. Children may overlap (their overlap
  /// counts twice in the mass). Refused with the child's index: another
  /// shape type, an unknown hull, sizes out of range, a non-finite pose.
  Result<GeometryId> add_compound(std::span<const CompoundChild> children);

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

  /// A compound's summary (its centre_of_mass, principal_axes and
  /// unit_inertia as a hull's; vertex, face and edge counts zero), or
  /// nullopt when `id` is not a compound.
  std::optional<HullInfo> compound_info(GeometryId id) const;
  /// A hull's summary, or nullopt when `id` is not a hull.
  std::optional<HullInfo> hull_info(GeometryId id) const;
  /// A hull's corners in the frame its points were given in (after
  /// snapping), for drawing; `out` is cleared first (empty for a non-hull).
  void hull_vertices(GeometryId id, std::vector<Vec3>& out) const;

  /// The engine's form of a hull (internal), or nullptr when `id` is not a
  /// hull. The pointer stays valid for the store's lifetime.
  const d3::Hull* hull(uint32_t id) const;
  /// The same for meshes and height fields.
  const d3::TriangleMesh* mesh(uint32_t id) const;
  const d3::HeightField* height_field(uint32_t id) const;
  const d3::Compound* compound(uint32_t id) const;

 private:
  struct Entry;
  template <class T>
  Result<GeometryId> add_built(Result<T> built);
  Result<GeometryId> add(Entry entry);

  std::vector<Entry> entries_;
};

}  // namespace rwd::sim
