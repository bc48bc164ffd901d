// SPDX-License-Identifier: MIT
#include "rewind/viewer/replay_player.h"

#include <algorithm>
#include <span>
#include <utility>

namespace rwd::viewer {

Result<std::unique_ptr<ReplayPlayer>> ReplayPlayer::create(ViewBundle bundle,
                                                           uint32_t keyframe_every,
                                                           uint32_t max_keyframes) {
  auto sim = game::Simulation::create(bundle.game, bundle.setup);
  if (!sim.ok()) return sim.status();
  if (bundle.first_tick < 0 || (bundle.first_tick > 0 && bundle.start_state.empty())) {
    return Status::Error(
        ErrorCode::kInvalidArgument,
        "a bundle from tick " + std::to_string(bundle.first_tick) + " needs the state before it");
  }
  if (!bundle.start_state.empty()) {
    if (Status s = (*sim)->deserialize(bundle.start_state); !s.ok()) {
      return Status::Error(ErrorCode::kCorrupt, "the start state does not load: " + s.message());
    }
    if ((*sim)->tick() != bundle.first_tick) {
      return Status::Error(ErrorCode::kCorrupt, "the start state is at tick " +
                                                    std::to_string((*sim)->tick()) +
                                                    ", not the bundle's first tick " +
                                                    std::to_string(bundle.first_tick));
    }
  }
  keyframe_every = std::clamp(keyframe_every, 1u, 3600u);
  return std::unique_ptr<ReplayPlayer>(
      new ReplayPlayer(std::move(bundle), std::move(*sim), keyframe_every, max_keyframes));
}

ReplayPlayer::ReplayPlayer(ViewBundle bundle, std::unique_ptr<game::Simulation> sim,
                           uint32_t keyframe_every, uint32_t max_keyframes)
    : bundle_(std::move(bundle)),
      sim_(std::move(sim)),
      keyframe_every_(keyframe_every),
      max_keyframes_(max_keyframes) {
  keyframes_.resize(bundle_.tick_count() / keyframe_every_ + 1);
  checks_.assign(bundle_.tick_count() + 1, TickCheck::kUnchecked);
  verified_ = bundle_.first_tick;
  keep_keyframe();
}

void ReplayPlayer::keep_keyframe() {
  const size_t at = offset(position());
  if (at % keyframe_every_ != 0) return;
  std::optional<game::SimSnapshot>& slot = keyframes_[at / keyframe_every_];
  if (slot) return;
  slot.emplace();
  sim_->save(*slot);
  ++kept_keyframes_;
  // Over the bound: the oldest kept goes, but never the first (the only
  // way back to the start).
  for (size_t k = 1;
       max_keyframes_ > 0 && kept_keyframes_ > max_keyframes_ && k < keyframes_.size(); ++k) {
    if (k != at / keyframe_every_ && keyframes_[k]) {
      keyframes_[k].reset();
      --kept_keyframes_;
    }
  }
}

Status ReplayPlayer::append(const LiveTicks& batch) {
  const uint32_t players = bundle_.setup.player_count;
  if (batch.player_count != players) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "the batch is for " + std::to_string(batch.player_count) +
                             " players, the match has " + std::to_string(players));
  }
  if (batch.first_tick > length()) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "the batch starts at tick " + std::to_string(batch.first_tick) +
                             ", after a gap from " + std::to_string(length()));
  }
  if (!batch.player_names.empty()) bundle_.player_names = batch.player_names;
  const size_t skip = static_cast<size_t>(length() - batch.first_tick);
  for (size_t i = skip; i < batch.checksums.size(); ++i) {
    bundle_.checksums.push_back(batch.checksums[i]);
    bundle_.substituted_masks.push_back(batch.substituted_masks[i]);
    bundle_.inputs.insert(bundle_.inputs.end(), batch.inputs.begin() + i * players,
                          batch.inputs.begin() + (i + 1) * players);
  }
  keyframes_.resize(bundle_.tick_count() / keyframe_every_ + 1);
  checks_.resize(bundle_.tick_count() + 1, TickCheck::kUnchecked);
  return Status::Ok();
}

bool ReplayPlayer::step() {
  const Tick p = position();
  if (p >= length()) return false;
  const uint32_t players = bundle_.setup.player_count;
  const size_t i = offset(p);
  if (!sim_->step(std::span<const rwd::PlayerInput>(bundle_.inputs).subspan(i * players, players))
           .ok()) {
    // The rules failed where the match did not: the tick cannot match.
    record_check(p + 1, ~bundle_.checksums[i]);
    return false;
  }
  record_check(p + 1, sim_->checksum());
  // Stepping from the start (or from states it made itself) verifies.
  if (!jumped_ && verified_ == p) verified_ = p + 1;
  keep_keyframe();
  return true;
}

void ReplayPlayer::record_check(Tick position, uint64_t checksum) {
  const size_t i = offset(position);
  const bool match = checksum == bundle_.checksums[i - 1];
  checks_[i] = match ? TickCheck::kMatch : TickCheck::kMismatch;
  if (!match && (!first_mismatch_ || *first_mismatch_ > position)) first_mismatch_ = position;
}

Tick ReplayPlayer::verify(uint32_t max_steps) {
  if (verified_ >= length()) return verified_;
  if (!verifier_) {
    auto sim = game::Simulation::create(bundle_.game, bundle_.setup);
    if (!sim.ok()) return verified_;
    verifier_ = std::move(*sim);
    if (!bundle_.start_state.empty() && !verifier_->deserialize(bundle_.start_state).ok()) {
      verifier_.reset();
      return verified_;
    }
    // Behind the player's own stepping, which verified up to verified_.
    while (verifier_->tick() < verified_) {
      const size_t i = offset(verifier_->tick());
      const uint32_t players = bundle_.setup.player_count;
      if (!verifier_
               ->step(
                   std::span<const rwd::PlayerInput>(bundle_.inputs).subspan(i * players, players))
               .ok()) {
        verifier_.reset();
        return verified_;
      }
    }
  }
  const uint32_t players = bundle_.setup.player_count;
  for (uint32_t n = 0; n < max_steps && verifier_->tick() < length(); ++n) {
    const size_t i = offset(verifier_->tick());
    if (!verifier_
             ->step(std::span<const rwd::PlayerInput>(bundle_.inputs).subspan(i * players, players))
             .ok()) {
      record_check(verifier_->tick() + 1, ~bundle_.checksums[i]);
      break;
    }
    record_check(verifier_->tick(), verifier_->checksum());
  }
  verified_ = std::max(verified_, verifier_->tick());
  return verified_;
}

void ReplayPlayer::seek(Tick target) {
  target = std::clamp(target, start(), length());
  const Tick now = position();
  if (target == now) return;
  // The nearest kept snapshot at or before the target; the present
  // position wins when it is nearer (a short scrub forward). The first
  // is always kept.
  Tick from = now <= target ? now : -1;
  const Tick every = static_cast<Tick>(keyframe_every_);
  Tick snapshot_at = -1;
  for (Tick k = (target - start()) / every; k >= 0; --k) {
    if (keyframes_[static_cast<size_t>(k)]) {
      snapshot_at = start() + k * every;
      break;
    }
  }
  // A recorded state nearer still saves the steps between.
  if (load_recorded_state(std::max(from, snapshot_at), target)) from = position();
  if (snapshot_at > from) {
    sim_->restore(*keyframes_[static_cast<size_t>((snapshot_at - start()) / every)]);
    from = snapshot_at;
  }
  while (position() < target && step()) {
  }
}

bool ReplayPlayer::load_recorded_state(Tick after, Tick target) {
  const std::vector<ViewKeyframe>& recorded = bundle_.keyframes;
  // The newest usable one in (after, target].
  for (size_t i = recorded.size(); i-- > 0;) {
    const ViewKeyframe& k = recorded[i];
    if (k.position > target) continue;
    if (k.position <= after) return false;
    if (unusable_.size() < recorded.size()) unusable_.resize(recorded.size(), false);
    if (unusable_[i]) continue;
    // Tried in a scratch simulation first: one that fails leaves the
    // player where it was.
    if (!scratch_) {
      auto sim = game::Simulation::create(bundle_.game, bundle_.setup);
      if (!sim.ok()) return false;
      scratch_ = std::move(*sim);
    }
    const bool usable = scratch_->deserialize(k.state).ok() && scratch_->tick() == k.position &&
                        scratch_->checksum() == bundle_.checksums[offset(k.position) - 1];
    // Loaded again into the player's own simulation, which renderers and
    // the cosmetic layer hold on to.
    if (!usable || !sim_->deserialize(k.state).ok()) {
      unusable_[i] = true;
      continue;
    }
    checks_[offset(k.position)] = TickCheck::kMatch;
    jumped_ = true;
    keep_keyframe();
    return true;
  }
  return false;
}

std::optional<uint64_t> ReplayPlayer::recorded_checksum() const {
  const Tick p = position();
  if (p <= start()) return std::nullopt;
  return bundle_.checksums[offset(p) - 1];
}

TickCheck ReplayPlayer::check(Tick p) const {
  if (p <= start() || p > length()) return TickCheck::kUnchecked;
  return checks_[offset(p)];
}

std::optional<std::array<double, 3>> ReplayPlayer::body_center(uint32_t index) const {
  std::vector<rwd::BodyField> fields;
  sim_->dump_bodies(fields);
  std::array<double, 3> at{};
  bool found = false;
  for (const rwd::BodyField& f : fields) {
    if (f.body_index != index) continue;
    // The 3D lane dumps position.x/y/z, the 2D lane center.x/y.
    const std::string_view n = f.name;
    const int axis = (n == "position.x" || n == "center.x")   ? 0
                     : (n == "position.y" || n == "center.y") ? 1
                     : n == "position.z"                      ? 2
                                                              : -1;
    if (axis < 0) continue;
    at[static_cast<size_t>(axis)] = f.value();
    found = true;
  }
  if (!found) return std::nullopt;
  return at;
}

Result<DesyncView> ReplayPlayer::open_desync() {
  if (!bundle_.desync) return Status::Error(ErrorCode::kNotFound, "the bundle holds no desync");
  const ViewDesync& d = *bundle_.desync;
  if (d.tick + 1 > length() || d.tick + 1 < start()) {
    return Status::Error(ErrorCode::kNotFound, "the desync's tick " + std::to_string(d.tick) +
                                                   " is outside the replay's ticks " +
                                                   std::to_string(start()) + " to " +
                                                   std::to_string(length()));
  }
  auto client = game::Simulation::create(bundle_.game, bundle_.setup);
  if (!client.ok()) return client.status();
  if (Status s = (*client)->deserialize(d.client_state); !s.ok()) {
    return Status::Error(ErrorCode::kCorrupt, "the client's state does not load: " + s.message());
  }
  seek(d.tick + 1);
  DesyncView view;
  view.position = position();
  view.client_checksum = (*client)->checksum();
  view.replay_checksum = checksum();
  std::vector<rwd::BodyField> expected;
  std::vector<rwd::BodyField> actual;
  sim_->dump_bodies(expected);
  (*client)->dump_bodies(actual);
  view.differences = rwd::diff_body_fields(expected, actual);
  for (const rwd::FieldDifference& f : view.differences) view.bodies.push_back(f.body_index);
  std::sort(view.bodies.begin(), view.bodies.end());
  view.bodies.erase(std::unique(view.bodies.begin(), view.bodies.end()), view.bodies.end());
  return view;
}

}  // namespace rwd::viewer
