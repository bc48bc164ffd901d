// SPDX-License-Identifier: MIT
// The geometry store: registration (validate, build, hash once) and lookup.
#include "rewind/sim/geometry.h"

#include <string>

#include "d3/hull.h"
#include "d3/hull_builder.h"
#include "rewind/sim/state_hasher.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {

struct GeometryStore::Entry {
  GeometryKind kind = GeometryKind::kHull;
  uint64_t hash = 0;
  std::unique_ptr<const d3::Hull> hull;
};

namespace {

// Everything the simulation reads of a hull, in a fixed order: two hulls
// with equal hashes collide, weigh and turn alike.
uint64_t hash_hull(const d3::Hull& h) {
  StateHasher s;
  s.add_u8(static_cast<uint8_t>(GeometryKind::kHull));
  s.add_u32(static_cast<uint32_t>(h.vertices.size()));
  for (const Vec3& v : h.vertices) s.add_vec3(v);
  s.add_u32(static_cast<uint32_t>(h.faces.size()));
  for (const d3::HullFace& f : h.faces) {
    s.add_vec3(f.normal);
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
  s.add_vec3(h.frame.center);
  s.add_quat(h.frame.rotation);
  s.add_f32(h.volume);
  s.add_vec3(h.unit_inertia);
  s.add_f32(h.extent);
  s.add_vec3(h.half_size);
  return s.digest();
}

bool same_hull(const d3::Hull& a, const d3::Hull& b) {
  if (a.vertices.size() != b.vertices.size()) return false;
  for (size_t i = 0; i < a.vertices.size(); ++i) {
    if (!(a.vertices[i] == b.vertices[i])) return false;
  }
  return a.frame.center == b.frame.center && a.frame.rotation == b.frame.rotation;
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
  Result<d3::Hull> hull = d3::make_hull(snapped(points));
  if (!hull.ok()) return hull.status();
  return add(std::make_unique<d3::Hull>(std::move(*hull)));
}

Result<GeometryId> GeometryStore::add_hull_from_points(std::span<const Vec3> points) {
  Result<d3::Hull> hull = d3::hull_from_points(snapped(points));
  if (!hull.ok()) return hull.status();
  return add(std::make_unique<d3::Hull>(std::move(*hull)));
}

Result<GeometryId> GeometryStore::add(std::unique_ptr<d3::Hull> hull) {
  const uint64_t h = hash_hull(*hull);
  for (uint32_t i = 0; i < entries_.size(); ++i) {
    const Entry& e = entries_[i];
    if (e.hash == h && e.kind == GeometryKind::kHull && same_hull(*e.hull, *hull)) {
      return GeometryId{i};
    }
  }
  if (entries_.size() >= kMaxEntries) {
    return Status::Error(ErrorCode::kCapacity,
                         "geometry store is full (" + std::to_string(kMaxEntries) + " entries)");
  }
  Entry e;
  e.kind = GeometryKind::kHull;
  e.hash = h;
  e.hull = std::move(hull);
  entries_.push_back(std::move(e));
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
