// SPDX-License-Identifier: MIT
// The checksum and the readable dump: the two places the 2D lane meets the
// shared hasher and field types, which name floating-point types for the
// 3D lane. Only integers flow through here; the float check of the step
// (sim2d_no_float_*) lists this file as its boundary.
#include <type_traits>
#include <vector>

#include "rewind/core/body_field.h"
#include "rewind/core/state_hasher.h"
#include "rewind/sim2d/world2d.h"
#include "state_schema2d.h"

namespace rwd::sim2d {

using namespace detail;

namespace {

class HashVisitor {
 public:
  explicit HashVisitor(rwd::StateHasher& hasher) : hasher_(hasher) {}
  template <class T>
  void operator()(std::string_view, const T& field) {
    if constexpr (std::is_same_v<T, Fx>) {
      hasher_.add_i32(field.raw());
    } else if constexpr (sizeof(T) == 8) {
      hasher_.add_u64(static_cast<uint64_t>(field));
    } else if constexpr (sizeof(T) == 1) {
      hasher_.add_u8(static_cast<uint8_t>(field));
    } else {
      hasher_.add_u32(static_cast<uint32_t>(field));
    }
  }

 private:
  rwd::StateHasher& hasher_;
};

class DumpVisitor {
 public:
  DumpVisitor(std::vector<rwd::BodyField>& out, uint32_t index) : out_(out), index_(index) {}
  template <class T>
  void operator()(std::string_view name, const T& field) {
    if constexpr (std::is_same_v<T, Fx>) {
      out_.push_back(rwd::BodyField::fixed16(index_, name, field.raw()));
    } else if constexpr (std::is_same_v<T, W>) {
      out_.push_back(rwd::BodyField::fixed32(index_, name, field));
    } else {
      out_.push_back(rwd::BodyField::unsigned_int(index_, name, static_cast<uint64_t>(field)));
    }
  }

 private:
  std::vector<rwd::BodyField>& out_;
  uint32_t index_;
};

}  // namespace

void World2D::hash_state(const World2DState& state, rwd::StateHasher& hasher) {
  HashVisitor v(hasher);
  visit_config(state.config, v);
  hasher.add_u64(state.step_count);
  hasher.add_u32(static_cast<uint32_t>(state.bodies.size()));
  for (const BodyRecord2D& body : state.bodies) {
    visit_slot_head(body, v);
    if (body.flags & kBodyLive) visit_body_rest(body, v);
  }
  hasher.add_u32(static_cast<uint32_t>(state.contacts.size()));
  for (const ContactRecord2D& contact : state.contacts) visit_contact(contact, v);
  hasher.add_u32(static_cast<uint32_t>(state.pending_exits.size()));
  for (const PendingExit2D& exit : state.pending_exits) visit_pending_exit(exit, v);
  hasher.add_u32(static_cast<uint32_t>(state.joints.size()));
  for (const JointRecord2D& joint : state.joints) {
    visit_joint_head(joint, v);
    if (joint.flags & kJointLive) visit_joint_rest(joint, v);
  }
}

void World2D::hash(rwd::StateHasher& hasher) const {
  hash_state(state_, hasher);
}

uint64_t World2D::checksum() const {
  rwd::StateHasher hasher;
  hash(hasher);
  return hasher.digest();
}

void World2D::dump_fields(std::vector<rwd::BodyField>& out) const {
  out.clear();
  for (uint32_t i = 0; i < state_.bodies.size(); ++i) {
    const BodyRecord2D& body = state_.bodies[i];
    if (!(body.flags & kBodyLive)) continue;
    DumpVisitor v(out, i);
    visit_slot_head(body, v);
    visit_body_rest(body, v);
  }
}

}  // namespace rwd::sim2d
