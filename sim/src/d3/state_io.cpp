// SPDX-License-Identifier: MIT
// Canonical views of WorldState: the checksum (fields fed to StateHasher in
// a fixed order) and the portable byte encoding (little-endian, field by
// field, magic + version). Both walk the same fields in the same order, so
// a deserialized world has the checksum of the serialized one. Derived data
// (mass properties, live count, free list) is neither hashed nor encoded:
// it is a function of what is. What a valid body is comes from
// state_rules.h, the rule the step keeps too.
#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "d3/body_storage.h"
#include "d3/pipeline.h"
#include "d3/shape_ops.h"
#include "d3/state_rules.h"
#include "d3/state_schema.h"
#include "rewind/sim/world3d.h"

namespace rwd::sim {
namespace {

constexpr uint8_t kMagic[4] = {'R', 'W', 'D', '3'};
// 2: world bounds in the config, the enabled flag per body. 3: each contact
// record's manifold frame and its points' positions on A (manifold reuse).
// 4: capsules (each shape's half height), rotation locks and torques.
// 5: hulls (a geometry id in place of sizes), the digest of the geometry
// the state refers to, and each body's continuous and contact-events flags.
// 6: joint slots after the contacts. 7: scheduled queries after the
// joints; each body's event mask in its contact-events byte. 8: the free
// spin's gyroscopic carry (sim revision 11). 9: each contact record's part
// (a compound pair has one record per group of contact normals).
constexpr uint32_t kVersion = 9;
// Starts the scheduled queries in the checksum's stream.
constexpr uint32_t kQueriesTag = 0x53514451u;  // "QDQS"
// Bounds the allocation a hostile header can request.
constexpr uint32_t kMaxSlots = 1u << 24;

// Streams the canonical fields into a hasher (Out = StateHasher) or a byte
// buffer (Out = std::vector<uint8_t>); both emit the same bytes in the same
// order. The checksum of every final tick walks every field of the state
// (thousands), so the hashing side gathers the fields in a block of its own,
// inlined, and hands the hasher whole blocks: one call per block instead of
// a call per field. Streaming XXH3 hashes the same bytes to the same value
// however they are split.
// The hashing side's block of gathered fields, kept apart from the Sink so
// that the Sink's cursor can live in a register: a byte store into the
// block cannot then be taken for a write to the cursor.
struct HashBlock {
  // Handed to the hasher once past kFlushAt, checked at the start of each
  // record; a record (a body, a contact, a joint: a few hundred bytes at
  // most) then always fits in what is left, so a field is written with no
  // check of its own.
  static constexpr size_t kFlushAt = 1024;
  static constexpr size_t kRecordMax = 1024;
  uint8_t bytes[kFlushAt + kRecordMax];
};

template <class Out>
class Sink {
 public:
  explicit Sink(Out& out) requires(!std::is_same_v<Out, StateHasher>)
      : out_(out), block_(nullptr) {}
  Sink(Out& out, HashBlock& block) requires std::is_same_v<Out, StateHasher>
      : out_(out), block_(block.bytes) {}
  Sink(const Sink&) = delete;
  Sink& operator=(const Sink&) = delete;
  ~Sink() {
    if constexpr (kHashing) flush();
  }
  /// Starts a record of at most HashBlock::kRecordMax bytes.
  [[gnu::always_inline]] void record() {
    if constexpr (kHashing) {
      if (used_ > HashBlock::kFlushAt) flush();
    }
  }
  [[gnu::always_inline]] void u8(uint8_t v) { put(&v, 1); }
  [[gnu::always_inline]] void u32(uint32_t v) {
    // One little-endian store per field: the encoding is little-endian on
    // every host, and a store of four bytes at once is what keeps the
    // checksum of thousands of fields cheap.
    if constexpr (std::endian::native == std::endian::big) v = byteswap32(v);
    uint8_t b[4];
    std::memcpy(b, &v, 4);
    put(b, 4);
  }
  [[gnu::always_inline]] void u64(uint64_t v) {
    u32(static_cast<uint32_t>(v));
    u32(static_cast<uint32_t>(v >> 32));
  }
  [[gnu::always_inline]] void f32(float v) {
    uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    // The checksum folds -0 onto +0, as StateHasher::add_f32 does, so two
    // equal values always hash alike; the encoding keeps the bits. On the
    // bits, not the float: no compare that a NaN could take either way.
    if constexpr (kHashing) bits = bits == 0x80000000u ? 0u : bits;
    u32(bits);
  }
  [[gnu::always_inline]] void vec3(Vec3 v) {
    f32(v.x);
    f32(v.y);
    f32(v.z);
  }
  [[gnu::always_inline]] void quat(Quat q) {
    f32(q.x);
    f32(q.y);
    f32(q.z);
    f32(q.w);
  }

 private:
  static constexpr bool kHashing = std::is_same_v<Out, StateHasher>;
  static constexpr uint32_t byteswap32(uint32_t v) {
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
  }
  [[gnu::always_inline]] void put(const uint8_t* bytes, size_t size) {
    if constexpr (kHashing) {
      assert(used_ + size <= sizeof(HashBlock::bytes) && "a record past HashBlock::kRecordMax");
      std::memcpy(block_ + used_, bytes, size);
      used_ += size;
    } else {
      const size_t at = out_.size();
      out_.resize(at + size);
      std::memcpy(out_.data() + at, bytes, size);
    }
  }
  void flush() {
    out_.add_bytes(block_, used_);
    used_ = 0;
  }
  Out& out_;
  uint8_t* block_;
  size_t used_ = 0;
};

// The schema's visitor over a Sink: names are for the dump only.
template <class Out>
class SinkIo {
 public:
  explicit SinkIo(Sink<Out>& s) : s_(s) {}
  [[gnu::always_inline]] void u8(const char*, uint8_t v) { s_.u8(v); }
  [[gnu::always_inline]] void flag(const char*, uint8_t v) { s_.u8(v); }
  [[gnu::always_inline]] void boolean(const char*, bool v) { s_.u8(v ? 1 : 0); }
  template <class E>
  [[gnu::always_inline]] void enumeration(const char*, E v, E) {
    s_.u8(static_cast<uint8_t>(v));
  }
  [[gnu::always_inline]] void count(const char*, uint8_t v, uint8_t) { s_.u8(v); }
  [[gnu::always_inline]] void event_mask(const char*, EventMask v) {
    s_.u8(d3::encode_event_mask(v));
  }
  [[gnu::always_inline]] void u32(const char*, uint32_t v) { s_.u32(v); }
  [[gnu::always_inline]] void i32(const char*, int32_t v) { s_.u32(static_cast<uint32_t>(v)); }
  [[gnu::always_inline]] void u64(const char*, uint64_t v) { s_.u64(v); }
  [[gnu::always_inline]] void f32(const char*, float v) { s_.f32(v); }
  [[gnu::always_inline]] void vec3(const char*, Vec3 v) { s_.vec3(v); }
  [[gnu::always_inline]] void quat(const char*, Quat q) { s_.quat(q); }

 private:
  Sink<Out>& s_;
};

template <class Out>
void write_config(Sink<Out>& s, const WorldConfig& c) {
  SinkIo<Out> io(s);
  s.record();
  d3::visit_config(io, c);
}

template <class Out>
void write_joints(Sink<Out>& s, const WorldState& st) {
  SinkIo<Out> io(s);
  s.record();
  s.u32(static_cast<uint32_t>(st.joints.size()));
  for (const JointRecord& j : st.joints) {
    s.record();
    s.u32(j.generation);
    s.u8(j.alive);
    if (j.alive != 0) d3::visit_joint(io, j);
  }
}

template <class Out>
void write_queries(Sink<Out>& s, const WorldState& st) {
  SinkIo<Out> io(s);
  s.record();
  s.u64(st.last_query_ticket);
  s.u32(static_cast<uint32_t>(st.queries.size()));
  for (const ScheduledQueryRecord& q : st.queries) {
    s.record();
    d3::visit_query(io, q);
  }
}

template <class Out>
void write_state(Sink<Out>& s, const WorldState& st) {
  write_config(s, st.config);
  SinkIo<Out> io(s);
  s.record();
  s.u64(st.step_count);
  s.u32(static_cast<uint32_t>(st.infos.size()));
  for (size_t i = 0; i < st.infos.size(); ++i) {
    const BodyInfo& b = st.infos[i];
    s.record();
    // Dead slots matter too: their generation decides the next id there.
    s.u32(b.generation);
    s.u8(b.alive);
    if (b.alive == 0) continue;
    d3::visit_body(io, b, st.sims[i]);
  }
  s.record();
  s.u32(static_cast<uint32_t>(st.contacts.size()));
  for (const ContactRecord& r : st.contacts) {
    s.record();
    d3::visit_contact(io, r);
  }
}

class Reader {
 public:
  explicit Reader(std::span<const uint8_t> b) : bytes_(b) {}
  bool ok() const { return ok_; }
  bool at_end() const { return pos_ == bytes_.size(); }
  size_t remaining() const { return bytes_.size() - pos_; }
  uint8_t u8() {
    if (pos_ + 1 > bytes_.size()) return fail();
    return bytes_[pos_++];
  }
  uint32_t u32() {
    if (pos_ + 4 > bytes_.size()) return fail();
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(bytes_[pos_ + i]) << (8 * i);
    pos_ += 4;
    return v;
  }
  uint64_t u64() {
    uint64_t lo = u32();
    uint64_t hi = u32();
    return lo | (hi << 32);
  }
  float f32() {
    uint32_t bits = u32();
    float v = 0.0f;
    std::memcpy(&v, &bits, 4);
    if (!std::isfinite(v)) ok_ = false;
    return v;
  }
  Vec3 vec3() {
    Vec3 v;
    v.x = f32();
    v.y = f32();
    v.z = f32();
    return v;
  }
  Quat quat() {
    Quat q;
    q.x = f32();
    q.y = f32();
    q.z = f32();
    q.w = f32();
    return q;
  }
  uint8_t flag() {
    uint8_t v = u8();
    if (v > 1) ok_ = false;
    return v;
  }
  void require(bool condition) {
    if (!condition) ok_ = false;
  }

 private:
  uint8_t fail() {
    ok_ = false;
    pos_ = bytes_.size();
    return 0;
  }
  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
  bool ok_ = true;
};

Status corrupt(const char* what) {
  return Status::Error(ErrorCode::kCorrupt, what);
}

// The schema's visitor over a Reader: fills the fields in order, and marks
// the input malformed (Reader::ok) at the first value out of its range.
class ReaderIo {
 public:
  explicit ReaderIo(Reader& r) : r_(r) {}
  void u8(const char*, uint8_t& v) { v = r_.u8(); }
  void flag(const char*, uint8_t& v) { v = r_.flag(); }
  void boolean(const char*, bool& v) { v = r_.flag() != 0; }
  template <class E>
  void enumeration(const char*, E& v, E last) {
    const uint8_t raw = r_.u8();
    const bool known = raw <= static_cast<uint8_t>(last);
    r_.require(known);
    v = known ? static_cast<E>(raw) : E{};
  }
  void count(const char*, uint8_t& v, uint8_t max) {
    v = r_.u8();
    if (v > max) {
      r_.require(false);
      v = 0;  // nothing follows a refused count
    }
  }
  void event_mask(const char*, EventMask& v) {
    const uint8_t raw = r_.u8();
    r_.require(d3::decode_event_mask(raw, v));
  }
  void u32(const char*, uint32_t& v) { v = r_.u32(); }
  void i32(const char*, int32_t& v) { v = static_cast<int32_t>(r_.u32()); }
  void u64(const char*, uint64_t& v) { v = r_.u64(); }
  void f32(const char*, float& v) { v = r_.f32(); }
  void vec3(const char*, Vec3& v) { v = r_.vec3(); }
  void quat(const char*, Quat& q) { q = r_.quat(); }

 private:
  Reader& r_;
};

// Reads the fields of a live body; the state rule judges them afterwards.
bool read_body(Reader& r, BodyInfo& b, BodySim& m) {
  ReaderIo io(r);
  d3::visit_body(io, b, m);
  return r.ok();
}

WorldConfig read_config(Reader& r) {
  WorldConfig c;
  ReaderIo io(r);
  d3::visit_config(io, c);
  return c;
}

// How many geometry entries the state refers to: one past the highest id a
// live body's or a scheduled overlap's shape names (0 when none uses
// geometry).
uint32_t geometry_used(const WorldState& st) {
  uint32_t used = 0;
  const auto use = [&used](const Shape& shape) {
    if (shape.uses_geometry() && shape.geometry + 1 > used) used = shape.geometry + 1;
  };
  for (const BodyInfo& b : st.infos) {
    if (b.alive != 0) use(b.shape);
  }
  for (const ScheduledQueryRecord& q : st.queries) {
    if (q.kind == ScheduledQueryKind::kOverlap) use(q.shape);
  }
  return used;
}

Status corrupt_body(uint32_t index, const std::string& why) {
  return Status::Error(ErrorCode::kCorrupt, "invalid body " + std::to_string(index) + ": " + why);
}

}  // namespace

void World3D::hash_state(const WorldState& state, StateHasher& hasher) {
  HashBlock block;
  Sink<StateHasher> sink(hasher, block);
  write_state(sink, state);
  // A world that never had a joint hashes as it did before joints existed,
  // and one that never scheduled a query as it did before queries could be.
  if (!state.joints.empty()) write_joints(sink, state);
  if (state.last_query_ticket != 0) {
    // Joints may have been absent: the queries' tag keeps the two sections
    // from reading as each other.
    sink.record();
    sink.u32(kQueriesTag);
    write_queries(sink, state);
  }
}

void World3D::serialize(std::vector<uint8_t>& out) const {
  out.clear();
  for (uint8_t b : kMagic) out.push_back(b);
  Sink<std::vector<uint8_t>> sink(out);
  sink.u32(kVersion);
  // The geometry this state refers to, so a world holding other geometry
  // refuses it instead of simulating other shapes under the same ids.
  const uint32_t used = geometry_used(state_);
  sink.u32(used);
  sink.u64(geometry_->digest(used));
  write_state(sink, state_);
  write_joints(sink, state_);
  write_queries(sink, state_);
}

void World3D::encode_config(const WorldConfig& config, std::vector<uint8_t>& out) {
  out.clear();
  Sink<std::vector<uint8_t>> sink(out);
  write_config(sink, config);
}

Result<WorldConfig> World3D::decode_config(std::span<const uint8_t> bytes) {
  Reader r(bytes);
  WorldConfig c = read_config(r);
  if (!r.ok() || !r.at_end()) return corrupt("malformed world config bytes");
  if (Status s = validate_config(c); !s.ok()) {
    return Status::Error(ErrorCode::kCorrupt, "invalid world config: " + s.message());
  }
  return c;
}

Status World3D::deserialize(std::span<const uint8_t> bytes) {
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, 4) != 0) {
    return corrupt("not a Rewind 3D world snapshot (bad magic)");
  }
  Reader r(bytes.subspan(4));
  if (r.u32() != kVersion) return corrupt("unsupported snapshot version");
  const GeometryStore& store = *geometry_;
  const uint32_t geometry_count = r.u32();
  const uint64_t geometry_digest = r.u64();
  if (!r.ok()) return corrupt("truncated snapshot header");
  if (geometry_count > store.size()) {
    return Status::Error(ErrorCode::kCorrupt, "snapshot refers to " +
                                                  std::to_string(geometry_count) +
                                                  " geometry entries; this world's store has " +
                                                  std::to_string(store.size()));
  }
  if (geometry_digest != store.digest(geometry_count)) {
    return corrupt(
        "snapshot was taken with other geometry (hull digests differ): register the same "
        "geometry in the same order first");
  }
  WorldState st;  // built aside: the live state changes only on success
  st.config = read_config(r);
  const WorldConfig& c = st.config;
  if (!r.ok()) return corrupt("truncated world config");
  if (Status s = validate_config(c); !s.ok()) {
    return Status::Error(ErrorCode::kCorrupt, "invalid world config: " + s.message());
  }
  st.step_count = r.u64();
  uint32_t slots = r.u32();
  // Every slot takes at least 5 bytes; reject counts the input cannot hold.
  if (!r.ok() || slots > kMaxSlots || slots > r.remaining() / 5) {
    return corrupt("bad body slot count");
  }
  st.infos.resize(slots);
  st.sims.resize(slots);
  st.masses.resize(slots);
  for (uint32_t i = 0; i < slots; ++i) {
    BodyInfo& b = st.infos[i];
    b.generation = r.u32();
    b.alive = r.flag();
    if (!r.ok()) return corrupt("truncated body");
    if (b.alive == 0) continue;
    if (!read_body(r, b, st.sims[i])) return corrupt_body(i, "truncated or malformed fields");
    if (Status s = d3::check_body(c, store, b, st.sims[i]); !s.ok()) {
      return corrupt_body(i, s.message());
    }
    if (b.shape.uses_geometry()) {
      if (b.shape.geometry >= geometry_count) {
        return corrupt_body(i, "geometry id past the snapshot's geometry count");
      }
      d3::shape_ops(b.shape.type).canonical(b.shape, store);  // its sizes, from the store
    }
    st.masses[i] = d3::compute_mass(b.kind, b.shape, store, b.density);
    if (Status s = d3::check_mass(b.kind, st.masses[i]); !s.ok()) {
      return corrupt_body(i, s.message());
    }
    ++st.live_count;
  }
  if (st.live_count > c.max_bodies) return corrupt("more bodies than max_bodies");
  for (uint32_t i = slots; i-- > 0;) {
    if (st.infos[i].alive == 0) st.free_slots.push_back(i);
  }
  uint32_t contacts = r.u32();
  if (!r.ok() || contacts > r.remaining() / 20) return corrupt("bad contact count");
  st.contacts.resize(contacts);
  for (uint32_t k = 0; k < contacts; ++k) {
    ContactRecord& rec = st.contacts[k];
    ReaderIo io(r);
    d3::visit_contact(io, rec);
    if (!r.ok()) return corrupt("invalid contact record");
    if (Status s = d3::check_contact(st.infos, rec, k > 0 ? &st.contacts[k - 1] : nullptr);
        !s.ok()) {
      return Status::Error(ErrorCode::kCorrupt,
                           "invalid contact record " + std::to_string(k) + ": " + s.message());
    }
  }
  const uint32_t joints = r.u32();
  // Every slot takes at least 5 bytes.
  if (!r.ok() || joints > kMaxSlots || joints > r.remaining() / 5) {
    return corrupt("bad joint slot count");
  }
  st.joints.resize(joints);
  for (uint32_t k = 0; k < joints; ++k) {
    JointRecord& j = st.joints[k];
    j.generation = r.u32();
    j.alive = r.flag();
    if (!r.ok()) return corrupt("truncated joint");
    if (j.alive == 0) continue;
    ReaderIo io(r);
    d3::visit_joint(io, j);
    if (!r.ok()) {
      return Status::Error(ErrorCode::kCorrupt, "invalid joint " + std::to_string(k) +
                                                    ": truncated or malformed fields");
    }
    if (Status s = d3::check_joint(c, st.infos, j); !s.ok()) {
      return Status::Error(ErrorCode::kCorrupt,
                           "invalid joint " + std::to_string(k) + ": " + s.message());
    }
    ++st.live_joints;
  }
  st.last_query_ticket = r.u64();
  const uint32_t queries = r.u32();
  // Every query takes at least 63 bytes (a ray's).
  if (!r.ok() || queries > World3D::kMaxScheduledQueries || queries > r.remaining() / 63) {
    return corrupt("bad scheduled query count");
  }
  st.queries.resize(queries);
  for (uint32_t k = 0; k < queries; ++k) {
    ScheduledQueryRecord& q = st.queries[k];
    ReaderIo io(r);
    d3::visit_query(io, q);
    const auto bad_query = [k](const std::string& why) {
      return Status::Error(ErrorCode::kCorrupt,
                           "invalid scheduled query " + std::to_string(k) + ": " + why);
    };
    if (!r.ok()) return bad_query("truncated or malformed fields");
    if (Status s =
            d3::check_query(store, q, st.last_query_ticket, k > 0 ? &st.queries[k - 1] : nullptr);
        !s.ok()) {
      return bad_query(s.message());
    }
    if (q.kind == ScheduledQueryKind::kOverlap && q.shape.uses_geometry()) {
      if (q.shape.geometry >= geometry_count) {
        return bad_query("geometry id past the snapshot's geometry count");
      }
      d3::shape_ops(q.shape.type).canonical(q.shape, store);
    }
  }
  if (!r.at_end()) return corrupt("trailing bytes after snapshot");
  state_ = std::move(st);
  d3::mark_world_edited(*scratch_);
  scratch_->events.clear();
  scratch_->body_events.clear();
  scratch_->broken_joints.clear();
  clear_step_queries();
  return Status::Ok();
}

}  // namespace rwd::sim
