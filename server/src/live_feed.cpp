// SPDX-License-Identifier: MIT
#include "rewind/server/live_feed.h"

#include <algorithm>
#include <utility>

#include "rewind/viewer/live_ticks.h"
#include "rewind/viewer/view_bundle.h"

namespace rwd::server {
namespace {

/// Keyframes held: a viewer that starts from the newest still finds its
/// ticks after a poll or two, and one with a delay finds a visible one.
constexpr size_t kKeptKeyframes = 3;

}  // namespace

LiveFeed::LiveFeed(Info info) : info_(std::move(info)) {
  names_.assign(info_.setup.player_count, std::string());
}

void LiveFeed::publish_tick(Tick tick, std::span<const rwd::PlayerInput> inputs,
                            uint64_t substituted, uint64_t checksum) {
  if (inputs.size() != info_.setup.player_count) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (tick != newest_ + 1 || ended_) return;
  checksums_.push_back(checksum);
  masks_.push_back(substituted);
  inputs_.insert(inputs_.end(), inputs.begin(), inputs.end());
  newest_ = tick;
  trim_locked();
}

void LiveFeed::publish_state(Tick position, std::span<const uint8_t> state) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (position != newest_ + 1 || state.empty() || ended_) return;
  if (!keyframes_.empty() && keyframes_.back().position >= position) return;
  keyframes_.push_back({position, std::vector<uint8_t>(state.begin(), state.end())});
  trim_locked();
}

void LiveFeed::publish_names(std::vector<std::string> names) {
  if (names.size() != info_.setup.player_count) return;
  for (std::string& name : names) {
    if (name.size() > viewer::kViewMaxString) name.resize(viewer::kViewMaxString);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  names_ = std::move(names);
}

void LiveFeed::end() {
  std::lock_guard<std::mutex> lock(mutex_);
  ended_ = true;
}

Tick LiveFeed::published_locked() const {
  if (ended_) return newest_;
  return std::max(kNoTick, newest_ - static_cast<Tick>(info_.delay_ticks));
}

void LiveFeed::trim_locked() {
  const Tick visible = published_locked();
  // Two visible states stay: a viewer at the visible edge is then at least
  // one keyframe interval past the first tick held, even with a delay.
  while (keyframes_.size() > kKeptKeyframes && keyframes_[2].position <= visible + 1) {
    keyframes_.pop_front();
    const Tick new_base = keyframes_.front().position;
    const size_t drop = static_cast<size_t>(new_base - base_);
    checksums_.erase(checksums_.begin(), checksums_.begin() + static_cast<ptrdiff_t>(drop));
    masks_.erase(masks_.begin(), masks_.begin() + static_cast<ptrdiff_t>(drop));
    inputs_.erase(inputs_.begin(),
                  inputs_.begin() + static_cast<ptrdiff_t>(drop * info_.setup.player_count));
    base_ = new_base;
  }
}

void LiveFeed::copy_ticks_locked(Tick from, Tick through, std::vector<uint64_t>& checksums,
                                 std::vector<uint64_t>& masks,
                                 std::vector<rwd::PlayerInput>& inputs) const {
  const auto players = static_cast<ptrdiff_t>(info_.setup.player_count);
  for (Tick t = from; t <= through; ++t) {
    const auto i = static_cast<ptrdiff_t>(t - base_);
    checksums.push_back(checksums_[static_cast<size_t>(i)]);
    masks.push_back(masks_[static_cast<size_t>(i)]);
    inputs.insert(inputs.end(), inputs_.begin() + i * players, inputs_.begin() + (i + 1) * players);
  }
}

Status LiveFeed::start_bundle(std::vector<uint8_t>& out) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const Tick visible = published_locked();
  viewer::ViewBundle bundle;
  bundle.game = info_.game;
  bundle.setup = info_.setup;
  bundle.tick_rate_hz = info_.tick_rate_hz;
  bundle.player_names = names_;
  // The newest state spectators may see; tick 0 (from the setup) before
  // the first.
  const Keyframe* from = nullptr;
  for (const Keyframe& k : keyframes_) {
    if (k.position <= visible + 1) from = &k;
  }
  if (from == nullptr && base_ > 0) {
    // trim_locked() keeps the oldest keyframe visible: this is defensive.
    return Status::Error(ErrorCode::kNotFound, "no state visible to spectators yet");
  }
  bundle.first_tick = from != nullptr ? from->position : 0;
  if (from != nullptr) bundle.start_state = from->state;
  copy_ticks_locked(bundle.first_tick, visible, bundle.checksums, bundle.substituted_masks,
                    bundle.inputs);
  return viewer::encode_view_bundle(bundle, out);
}

Status LiveFeed::ticks_from(Tick from, std::vector<uint8_t>& out) const {
  if (from < 0) return Status::Error(ErrorCode::kInvalidArgument, "a negative tick");
  std::lock_guard<std::mutex> lock(mutex_);
  if (from < base_) {
    return Status::Error(ErrorCode::kNotFound, "tick " + std::to_string(from) +
                                                   " is no longer held (the feed starts at " +
                                                   std::to_string(base_) + "): start over");
  }
  const Tick visible = published_locked();
  viewer::LiveTicks batch;
  batch.player_count = info_.setup.player_count;
  batch.player_names = names_;
  batch.newest_final = newest_;
  batch.ended = ended_;
  batch.first_tick = from;
  const Tick last = std::min(visible, from + static_cast<Tick>(viewer::kLiveMaxBatchTicks) - 1);
  copy_ticks_locked(from, last, batch.checksums, batch.substituted_masks, batch.inputs);
  return viewer::encode_live_ticks(batch, out);
}

LiveFeed::Summary LiveFeed::summary() const {
  std::lock_guard<std::mutex> lock(mutex_);
  Summary s;
  s.match_id = info_.match_id;
  s.game = info_.game;
  s.players = info_.setup.player_count;
  s.player_names = names_;
  s.newest_final = newest_;
  s.published = published_locked();
  s.tick_rate_hz = info_.tick_rate_hz;
  s.ended = ended_;
  return s;
}

}  // namespace rwd::server
