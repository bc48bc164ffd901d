// SPDX-License-Identifier: MIT
// The desync-drill perturbation: an ordinary teleport through the public
// API, so it obeys every rule a game's own set_transform() obeys.
#include <vector>

#include "rewind/sim/world3d.h"

namespace rwd::sim {

bool World3D::perturb_for_drill() {
  std::vector<BodyId> ids;
  body_ids(ids);
  for (auto it = ids.rbegin(); it != ids.rend(); ++it) {
    if (kind(*it) != BodyKind::kDynamic) continue;
    Vec3 p = position(*it);
    p.x += 0.001f;
    return set_transform(*it, p, rotation(*it)).ok();
  }
  return false;
}

}  // namespace rwd::sim
