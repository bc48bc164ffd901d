// SPDX-License-Identifier: MIT
// The geometry store: registration (validate, build, hash once) and lookup.
#include "rewind/sim/geometry.h"

#include <cmath>
#include <string>
#include <type_traits>

#include "d3/compound.h"
#include "d3/compound_builder.h"
#include "d3/height_field.h"
#include "d3/hull.h"
#include "d3/hull_builder.h"
#include "d3/mesh.h"
#include "rewind/sim/hash_math.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {

struct GeometryStore::Entry {
  GeometryKind kind = GeometryKind::kHull;
  uint64_t hash = 0;
  std::unique_ptr<const d3::Hull> hull;
  std::unique_ptr<const d3::TriangleMesh> mesh;
  std::unique_ptr<const d3::HeightField> height_field;
  std::unique_ptr<const d3::Compound> compound;
};

namespace {

// Everything the simulation reads of a hull, in a fixed order: two hulls
// with equal hashes collide, weigh and turn alike.
uint64_t hash_hull(const d3::Hull& h) {
  StateHasher s;
  s.add_u8(static_cast<uint8_t>(GeometryKind::kHull));
  s.add_u32(static_cast<uint32_t>(h.vertices.size()));
  for (const Vec3& v : h.vertices) hash_vec3(s, v);
  s.add_u32(static_cast<uint32_t>(h.faces.size()));
  for (const d3::HullFace& f : h.faces) {
    hash_vec3(s, f.normal);
    s.add_f32(f.offset);
    s.add_u32(f.first);
    s.add_u8(f.count);
  }
  s.add_u32(static_cast<uint32_t>(h.face_vertices.size()));
  for (uint8_t v : h.face_vertices) s.add_u8(v);
  s.add_u32(static_cast<uint32_t>(h.edges.size()));
  for (const d3::HullEdge& e : h.edges) {
    s.add_u8(e.v0);
    s.add_u8(e.v1);
    s.add_u8(e.face_left);
    s.add_u8(e.face_right);
  }
  hash_vec3(s, h.frame.center);
  hash_quat(s, h.frame.rotation);
  s.add_f32(h.volume);
  hash_vec3(s, h.unit_inertia);
  s.add_f32(h.extent);
  hash_vec3(s, h.half_size);
  return s.digest();
}

// The mesh as given (vertices, triangles, sidedness): the tree and the edge
// flags are functions of it.
uint64_t hash_mesh(const d3::TriangleMesh& m) {
  StateHasher s;
  s.add_u8(static_cast<uint8_t>(GeometryKind::kMesh));
  s.add_u8(m.one_sided ? 1 : 0);
  s.add_u32(static_cast<uint32_t>(m.vertices.size()));
  for (const Vec3& v : m.vertices) hash_vec3(s, v);
  s.add_u32(static_cast<uint32_t>(m.triangles.size()));
  for (const d3::MeshTriangle& t : m.triangles) {
    s.add_u32(t.v[0]);
    s.add_u32(t.v[1]);
    s.add_u32(t.v[2]);
  }
  return s.digest();
}

uint64_t hash_height_field(const d3::HeightField& h) {
  StateHasher s;
  s.add_u8(static_cast<uint8_t>(GeometryKind::kHeightField));
  s.add_u32(h.rows);
  s.add_u32(h.cols);
  hash_vec3(s, h.scale);
  for (float v : h.heights) s.add_f32(v);
  s.add_u32(static_cast<uint32_t>(h.holes.size()));
  for (uint8_t v : h.holes) s.add_u8(v);
  return s.digest();
}

// The children as built (canonical shapes, mass-frame poses; a hull child
// by its hash) and the mass frame.
uint64_t hash_compound(const d3::Compound& c, const GeometryStore& store) {
  StateHasher s;
  s.add_u8(static_cast<uint8_t>(GeometryKind::kCompound));
  s.add_u32(static_cast<uint32_t>(c.parts.size()));
  for (const d3::CompoundPart& p : c.parts) {
    s.add_u8(static_cast<uint8_t>(p.shape.type));
    s.add_f32(p.shape.radius);
    hash_vec3(s, p.shape.half_extents);
    s.add_f32(p.shape.half_height);
    s.add_u64(p.shape.uses_geometry() ? store.hash(GeometryId{p.shape.geometry}) : 0);
    hash_vec3(s, p.position);
    hash_quat(s, p.rotation);
  }
  hash_vec3(s, c.frame.center);
  hash_quat(s, c.frame.rotation);
  s.add_f32(c.volume);
  hash_vec3(s, c.unit_inertia);
  return s.digest();
}

bool same_points(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] == b[i])) return false;
  }
  return true;
}

// Equal hashes are checked field by field before two entries count as one.
bool same_entry(const GeometryStore& store, uint32_t id, GeometryKind kind, const d3::Hull* hull,
                const d3::TriangleMesh* mesh, const d3::HeightField* field,
                const d3::Compound* compound) {
  switch (kind) {
    case GeometryKind::kCompound: {
      const d3::Compound* c = store.compound(id);
      if (c == nullptr || c->parts.size() != compound->parts.size()) return false;
      for (size_t i = 0; i < c->parts.size(); ++i) {
        const d3::CompoundPart& a = c->parts[i];
        const d3::CompoundPart& b = compound->parts[i];
        if (a.shape.type != b.shape.type || a.shape.geometry != b.shape.geometry ||
            !(a.shape.half_extents == b.shape.half_extents) || a.shape.radius != b.shape.radius ||
            a.shape.half_height != b.shape.half_height || !(a.position == b.position) ||
            !(a.rotation == b.rotation)) {
          return false;
        }
      }
      return true;
    }
    case GeometryKind::kHull: {
      const d3::Hull* h = store.hull(id);
      return h != nullptr && same_points(h->vertices, hull->vertices) &&
             h->frame.center == hull->frame.center && h->frame.rotation == hull->frame.rotation;
    }
    case GeometryKind::kMesh: {
      const d3::TriangleMesh* m = store.mesh(id);
      if (m == nullptr || m->one_sided != mesh->one_sided ||
          m->triangles.size() != mesh->triangles.size() ||
          !same_points(m->vertices, mesh->vertices)) {
        return false;
      }
      for (size_t t = 0; t < m->triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
          if (m->triangles[t].v[k] != mesh->triangles[t].v[k]) return false;
        }
      }
      return true;
    }
    case GeometryKind::kHeightField: {
      const d3::HeightField* h = store.height_field(id);
      if (h == nullptr || h->rows != field->rows || h->cols != field->cols ||
          !(h->scale == field->scale) || h->holes != field->holes) {
        return false;
      }
      for (size_t i = 0; i < h->heights.size(); ++i) {
        if (!(h->heights[i] == field->heights[i])) return false;
      }
      return true;
    }
  }
  return false;
}

// Outside points enter the canonical grid first, so every client builds
// its hull from the same bits whatever parser produced them.
std::vector<Vec3> snapped(std::span<const Vec3> points) {
  std::vector<Vec3> out(points.begin(), points.end());
  for (Vec3& p : out) {
    if (is_finite(p)) p = quantize(p);
  }
  return out;
}

}  // namespace

GeometryStore::GeometryStore() = default;
GeometryStore::~GeometryStore() = default;

Result<GeometryId> GeometryStore::add_hull(std::span<const Vec3> points) {
  return add_built(d3::make_hull(snapped(points)));
}

Result<GeometryId> GeometryStore::add_hull_from_points(std::span<const Vec3> points) {
  return add_built(d3::hull_from_points(snapped(points)));
}

Result<GeometryId> GeometryStore::add_mesh(std::span<const Vec3> vertices,
                                           std::span<const uint32_t> indices, bool one_sided) {
  return add_built(d3::build_mesh(snapped(vertices), indices, one_sided));
}

Result<GeometryId> GeometryStore::add_height_field(uint32_t rows, uint32_t cols, Vec3 scale,
                                                   std::span<const float> heights,
                                                   std::span<const uint8_t> holes) {
  // Outside values enter the canonical grid, as points do.
  std::vector<float> on_grid(heights.begin(), heights.end());
  for (float& h : on_grid) {
    if (std::isfinite(h)) h = quantize(h);
  }
  const Vec3 s = is_finite(scale) ? quantize(scale) : scale;
  return add_built(d3::build_height_field(rows, cols, s, on_grid, holes));
}

Result<GeometryId> GeometryStore::add_compound(std::span<const CompoundChild> children) {
  return add_built(d3::build_compound(children, *this));
}

// A built piece of geometry (or why it was refused) as an entry: its kind,
// its hash, and the data behind the matching pointer.
template <class T>
Result<GeometryId> GeometryStore::add_built(Result<T> built) {
  if (!built.ok()) return built.status();
  Entry e;
  if constexpr (std::is_same_v<T, d3::Hull>) {
    e.kind = GeometryKind::kHull;
    e.hash = hash_hull(*built);
    e.hull = std::make_unique<d3::Hull>(std::move(*built));
  } else if constexpr (std::is_same_v<T, d3::TriangleMesh>) {
    e.kind = GeometryKind::kMesh;
    e.hash = hash_mesh(*built);
    e.mesh = std::make_unique<d3::TriangleMesh>(std::move(*built));
  } else if constexpr (std::is_same_v<T, d3::HeightField>) {
    e.kind = GeometryKind::kHeightField;
    e.hash = hash_height_field(*built);
    e.height_field = std::make_unique<d3::HeightField>(std::move(*built));
  } else {
    static_assert(std::is_same_v<T, d3::Compound>);
    e.kind = GeometryKind::kCompound;
    e.hash = hash_compound(*built, *this);
    e.compound = std::make_unique<d3::Compound>(std::move(*built));
  }
  return add(std::move(e));
}

Result<GeometryId> GeometryStore::add(Entry entry) {
  for (uint32_t i = 0; i < entries_.size(); ++i) {
    const Entry& e = entries_[i];
    if (e.hash == entry.hash && e.kind == entry.kind &&
        same_entry(*this, i, entry.kind, entry.hull.get(), entry.mesh.get(),
                   entry.height_field.get(), entry.compound.get())) {
      return GeometryId{i};
    }
  }
  if (entries_.size() >= kMaxEntries) {
    return Status::Error(ErrorCode::kCapacity,
                         "geometry store is full (" + std::to_string(kMaxEntries) + " entries)");
  }
  entries_.push_back(std::move(entry));
  return GeometryId{static_cast<uint32_t>(entries_.size() - 1)};
}

uint32_t GeometryStore::size() const {
  return static_cast<uint32_t>(entries_.size());
}

bool GeometryStore::contains(GeometryId id) const {
  return id.value < entries_.size();
}

std::optional<GeometryKind> GeometryStore::kind(GeometryId id) const {
  if (!contains(id)) return std::nullopt;
  return entries_[id.value].kind;
}

uint64_t GeometryStore::hash(GeometryId id) const {
  return contains(id) ? entries_[id.value].hash : 0;
}

uint64_t GeometryStore::digest(uint32_t count) const {
  StateHasher s;
  s.add_u32(count);
  for (uint32_t i = 0; i < count && i < entries_.size(); ++i) s.add_u64(entries_[i].hash);
  return s.digest();
}

const d3::Hull* GeometryStore::hull(uint32_t id) const {
  if (id >= entries_.size() || entries_[id].kind != GeometryKind::kHull) return nullptr;
  return entries_[id].hull.get();
}

const d3::TriangleMesh* GeometryStore::mesh(uint32_t id) const {
  if (id >= entries_.size() || entries_[id].kind != GeometryKind::kMesh) return nullptr;
  return entries_[id].mesh.get();
}

const d3::HeightField* GeometryStore::height_field(uint32_t id) const {
  if (id >= entries_.size() || entries_[id].kind != GeometryKind::kHeightField) return nullptr;
  return entries_[id].height_field.get();
}

const d3::Compound* GeometryStore::compound(uint32_t id) const {
  if (id >= entries_.size() || entries_[id].kind != GeometryKind::kCompound) return nullptr;
  return entries_[id].compound.get();
}

std::optional<HullInfo> GeometryStore::compound_info(GeometryId id) const {
  const d3::Compound* c = compound(id.value);
  if (c == nullptr) return std::nullopt;
  HullInfo info;
  info.volume = c->volume;
  info.center_of_mass = c->frame.center;
  info.principal_axes = c->frame.rotation;
  info.unit_inertia = c->unit_inertia;
  return info;
}

std::optional<HullInfo> GeometryStore::hull_info(GeometryId id) const {
  const d3::Hull* h = hull(id.value);
  if (h == nullptr) return std::nullopt;
  HullInfo info;
  info.vertex_count = static_cast<uint32_t>(h->vertices.size());
  info.face_count = static_cast<uint32_t>(h->faces.size());
  info.edge_count = static_cast<uint32_t>(h->edges.size());
  info.volume = h->volume;
  info.center_of_mass = h->frame.center;
  info.principal_axes = h->frame.rotation;
  info.unit_inertia = h->unit_inertia;
  return info;
}

void GeometryStore::hull_vertices(GeometryId id, std::vector<Vec3>& out) const {
  out.clear();
  const d3::Hull* h = hull(id.value);
  if (h == nullptr) return;
  for (const Vec3& v : h->vertices) out.push_back(rotate(h->frame.rotation, v) + h->frame.center);
}

}  // namespace rwd::sim
