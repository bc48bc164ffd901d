// SPDX-License-Identifier: MIT
#pragma once
// The 3D lane's vector types fed to the lane-neutral StateHasher, component
// by component in a fixed order.
#include "rewind/core/state_hasher.h"
#include "rewind/sim/math.h"

namespace rwd::sim {

inline void hash_vec3(StateHasher& hasher, const Vec3& v) {
  hasher.add_f32(v.x);
  hasher.add_f32(v.y);
  hasher.add_f32(v.z);
}

inline void hash_quat(StateHasher& hasher, const Quat& q) {
  hasher.add_f32(q.x);
  hasher.add_f32(q.y);
  hasher.add_f32(q.z);
  hasher.add_f32(q.w);
}

}  // namespace rwd::sim
