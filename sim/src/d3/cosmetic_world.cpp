// SPDX-License-Identifier: MIT
#include "rewind/sim/cosmetic_world.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "rewind/sim/debug_draw3d.h"

namespace rwd::sim {

Result<std::unique_ptr<CosmeticWorld>> CosmeticWorld::create(
    const CosmeticConfig& config, std::shared_ptr<GeometryStore> geometry) {
  if (Status s = World3D::validate_config(config.world); !s.ok()) return s;
  if (!(config.prop_lifetime_s > 0.0f) || !std::isfinite(config.prop_lifetime_s)) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "cosmetic world: prop_lifetime_s must be finite and > 0");
  }
  if (config.max_props == 0) {
    return Status::Error(ErrorCode::kInvalidArgument, "cosmetic world: max_props must be > 0");
  }
  return std::unique_ptr<CosmeticWorld>(new CosmeticWorld(config, std::move(geometry)));
}

CosmeticWorld::CosmeticWorld(const CosmeticConfig& config, std::shared_ptr<GeometryStore> geometry)
    : config_(config), world_(config.world, std::move(geometry)) {}

void CosmeticWorld::sync(const World3D& authority) {
  const WorldState& s = authority.state();
  auto wanted = [&](uint32_t i) {
    const BodyInfo& info = s.infos[i];
    if (info.alive == 0 || info.enabled == 0 || info.sensor != 0) return false;
    return info.kind != BodyKind::kDynamic || config_.proxy_dynamic_bodies;
  };
  // Proxies whose body is gone, changed hands or left the simulation go.
  std::vector<Proxy> kept;
  kept.reserve(proxies_.size());
  for (const Proxy& p : proxies_) {
    const bool same = p.authority_index < s.infos.size() &&
                      s.infos[p.authority_index].generation == p.authority_generation &&
                      wanted(p.authority_index);
    if (same) {
      kept.push_back(p);
    } else {
      (void)world_.destroy_body(p.body);
    }
  }
  proxies_ = std::move(kept);
  // New bodies get a proxy; moving ones follow. Both walks go by index.
  size_t next = 0;
  std::vector<Proxy> merged;
  merged.reserve(proxies_.size());
  for (uint32_t i = 0; i < s.infos.size(); ++i) {
    // A proxy kept above is of a body still wanted.
    if (!wanted(i)) continue;
    const bool has = next < proxies_.size() && proxies_[next].authority_index == i;
    const BodyInfo& info = s.infos[i];
    const BodyId id{i, info.generation};
    Proxy proxy;
    if (has) {
      proxy = proxies_[next++];
    } else {
      BodyDef def;
      def.kind = info.kind == BodyKind::kStatic ? BodyKind::kStatic : BodyKind::kKinematic;
      def.shape = info.shape;
      def.position = authority.position(id);
      def.rotation = authority.rotation(id);
      def.material = info.material;
      Result<BodyId> made = world_.create_body(def);
      if (!made.ok()) continue;  // a body this world refuses is left out
      proxy = {i, info.generation, *made, def.kind == BodyKind::kKinematic};
    }
    if (proxy.moving) {
      // Placed where the authority is, moving as it moves: the cosmetic
      // step carries it toward where the authority will be next, and props
      // it meets on the way are pushed as by the real body.
      (void)world_.set_transform(proxy.body, authority.position(id), authority.rotation(id));
      const bool still = teleport_;
      (void)world_.set_linear_velocity(proxy.body, still ? Vec3{} : authority.linear_velocity(id));
      (void)world_.set_angular_velocity(proxy.body,
                                        still ? Vec3{} : authority.angular_velocity(id));
    }
    merged.push_back(proxy);
  }
  proxies_ = std::move(merged);
  teleport_ = false;
}

Result<PropId> CosmeticWorld::add_prop(const BodyDef& def) {
  if (def.kind != BodyKind::kDynamic) {
    return Status::Error(ErrorCode::kInvalidArgument, "cosmetic world: a prop is a dynamic body");
  }
  Result<BodyId> made = world_.create_body(def);
  if (!made.ok()) return made.status();
  if (props_.size() >= config_.max_props) {
    (void)world_.destroy_body(props_.front().body);
    props_.erase(props_.begin());
  }
  props_.push_back({*made, world_.step_count()});
  return PropId{*made};
}

Status CosmeticWorld::remove_prop(PropId prop) {
  const auto it = std::find_if(props_.begin(), props_.end(),
                               [&](const Prop& p) { return p.body == prop.body; });
  if (it == props_.end())
    return Status::Error(ErrorCode::kNotFound, "cosmetic world: no such prop");
  (void)world_.destroy_body(it->body);
  props_.erase(it);
  return Status::Ok();
}

void CosmeticWorld::clear_props() {
  for (const Prop& p : props_) (void)world_.destroy_body(p.body);
  props_.clear();
}

bool CosmeticWorld::is_prop(PropId prop) const {
  return std::any_of(props_.begin(), props_.end(),
                     [&](const Prop& p) { return p.body == prop.body; });
}

void CosmeticWorld::step() {
  world_.step();
  const double tick = world_.config().tick_seconds;
  const uint64_t now = world_.step_count();
  size_t kept = 0;
  for (const Prop& p : props_) {
    if (static_cast<double>(now - p.born_step) * tick >= config_.prop_lifetime_s) {
      (void)world_.destroy_body(p.body);
    } else {
      props_[kept++] = p;
    }
  }
  props_.resize(kept);
}

void CosmeticWorld::draw_props(const DebugDrawOptions& options, DrawColor color,
                               DebugDrawBuffers& out) const {
  for (const Prop& p : props_) {
    const Shape* shape = world_.shape(p.body);
    if (shape == nullptr) continue;
    draw_shape(world_.geometry(), *shape, world_.position(p.body), world_.rotation(p.body), color,
               options, out);
  }
}

}  // namespace rwd::sim
