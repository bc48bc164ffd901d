// SPDX-License-Identifier: MIT
#include "rewind/server/match_recorder.h"

#include "host_log.h"

namespace rwd::server {

using detail::log_line;
using detail::log_warning;
using detail::worth_logging;

MatchRecorder::MatchRecorder(std::optional<replay::ReplayWriter> replay, uint32_t keyframe_interval)
    : replay_(std::move(replay)), keyframe_interval_(keyframe_interval) {}

void MatchRecorder::attach_live_feed(std::shared_ptr<LiveFeed> feed) {
  live_ = std::move(feed);
  names_stale_ = live_ != nullptr;
}

void MatchRecorder::record(net::RollbackSession& session, Tick t,
                           std::span<const rwd::PlayerInput> inputs, uint64_t substituted,
                           uint64_t checksum, MatchStats& stats) {
  bool serialized = false;  // state_buffer_ holds the state after t
  if (replay_ && !replay_failed_) {
    Status status = replay_->append_tick(t, inputs, substituted, checksum);
    if (status.ok() && keyframe_interval_ > 0 && (t + 1) % keyframe_interval_ == 0 &&
        session.serialize_state_at(t + 1, state_buffer_)) {
      serialized = true;
      // Checked as a resync snapshot is checked; one that fails is left out.
      if (auto loaded = session.load_snapshot(state_buffer_, checksum); loaded.ok()) {
        status = replay_->append_keyframe(t, state_buffer_);
      } else {
        ++stats.keyframe_load_failures;
        if (worth_logging(stats.keyframe_load_failures)) {
          log_warning("replay keyframe after tick " + std::to_string(t) +
                      " does not load on the server, left out: " + loaded.status().message() +
                      " (" + std::to_string(stats.keyframe_load_failures) + " so far)");
        }
      }
    }
    if (!status.ok()) stop_replay(status);
  }
  if (!live_) return;
  live_->publish_tick(t, inputs, substituted, checksum);
  if (live_->wants_state(t + 1) &&
      (serialized || session.serialize_state_at(t + 1, state_buffer_))) {
    live_->publish_state(t + 1, state_buffer_);
  }
}

void MatchRecorder::publish_names(std::vector<std::string> names) {
  if (live_) live_->publish_names(std::move(names));
  names_stale_ = false;
}

void MatchRecorder::flush_if_due() {
  if (!replay_ || replay_failed_) return;
  if (Status status = replay_->flush_if_due(); !status.ok()) stop_replay(status);
}

void MatchRecorder::finish(Tick last_final, const std::string& reason) {
  if (replay_ && !replay_failed_) {
    if (Status status = replay_->finish(last_final, reason); !status.ok()) stop_replay(status);
  }
  if (live_) live_->end();
}

void MatchRecorder::stop_replay(const Status& status) {
  replay_failed_ = true;
  log_line("replay writing stopped: " + status.message() +
           " (the file keeps its verified prefix; the match goes on)");
}

}  // namespace rwd::server
