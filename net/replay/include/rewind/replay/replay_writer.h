// SPDX-License-Identifier: MIT
#pragma once
// Append-only replay recording for the server's finalizer. Every record is
// framed and hashed on its own, and buffered frames reach the OS at least
// once per flush interval, on keyframes and on finish, so a server killed
// mid-match leaves a file whose prefix verifies.
#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rewind/core/player_input.h"
#include "rewind/core/status.h"
#include "rewind/core/tick.h"
#include "rewind/v1/replay.pb.h"

namespace rwd::replay {

/// How a ReplayWriter creates its file and when it flushes.
struct ReplayWriterOptions {
  using Clock = std::function<std::chrono::steady_clock::time_point()>;

  /// Replace an existing non-empty file instead of refusing it.
  bool overwrite = false;
  /// Buffered frames are handed to the OS once this much time has passed
  /// since the previous flush (checked on every append and flush_if_due()).
  std::chrono::milliseconds flush_interval{1000};
  /// Flush early once this many bytes are buffered.
  size_t flush_bytes = 1u << 20;
  /// Time source for the flush interval; empty means steady_clock::now.
  /// Tests pass a fake clock.
  Clock clock;
};

/// Writes one match's replay: header, then per final tick its inputs and
/// checksum, keyframes when the caller has them, and an end record.
///
/// Ticks must arrive in order starting at 0. Invalid calls (gaps, wrong input
/// counts) return kInvalidArgument and change nothing. An operating-system
/// error (disk full, I/O error) returns kIo and is sticky: every later call
/// returns it too, because the file's tail is then unknown.
class ReplayWriter {
 public:
  /// Creates or truncates `path`, writes the magic and `header` and flushes
  /// them. A format_version of 0 becomes kFormatVersion; an older readable
  /// version is kept (copies of old files stay what they were). The header
  /// must pass validate_header(): a format 2 header carries the engine
  /// identity (make_replay_header() in replay_header.h fills it). Refuses an
  /// existing non-empty file unless options.overwrite.
  static Result<ReplayWriter> open(const std::string& path, const v1::ReplayHeader& header,
                                   ReplayWriterOptions options = {});

  ReplayWriter(ReplayWriter&& other) noexcept;
  ReplayWriter& operator=(ReplayWriter&& other) noexcept;
  ReplayWriter(const ReplayWriter&) = delete;
  ReplayWriter& operator=(const ReplayWriter&) = delete;
  /// Flushes what is buffered (best effort, no fsync) and closes the file.
  ~ReplayWriter();

  /// Records final tick `tick` (must be last_tick() + 1): one input per
  /// player slot, bit p of `substituted_mask` set when player p's input was
  /// substituted, and the world checksum after stepping `tick`.
  Status append_tick(Tick tick, std::span<const rwd::PlayerInput> inputs, uint64_t substituted_mask,
                     uint64_t checksum);

  /// Records the serialized simulation state after `tick`, which must be the
  /// last appended tick (or kNoTick before the first one, for the initial
  /// state). Flushes.
  Status append_keyframe(Tick tick, std::span<const uint8_t> serialized_state);

  /// Writes the end record, flushes, fsyncs and closes. `last_final_tick`
  /// must equal last_tick(). Nothing can be appended afterwards.
  Status finish(Tick last_final_tick, std::string_view reason);

  /// Hands every buffered frame to the OS now.
  Status flush();
  /// Flushes if the flush interval has passed; call from an idle timer so a
  /// stalled match still reaches the disk.
  Status flush_if_due();

  /// The last tick appended, kNoTick before the first.
  Tick last_tick() const { return last_tick_; }
  const std::string& path() const { return path_; }
  bool finished() const { return finished_; }
  /// Bytes handed to the OS so far (magic included).
  uint64_t bytes_flushed() const { return bytes_flushed_; }
  /// Bytes appended but not yet handed to the OS.
  size_t bytes_buffered() const { return buffer_.size(); }

 private:
  ReplayWriter(std::string path, int fd, const v1::ReplayHeader& header,
               ReplayWriterOptions options);
  Status usable() const;
  Status maybe_flush();
  void close_fd();

  std::string path_;
  int fd_ = -1;
  uint32_t player_count_ = 0;
  bool stick_inputs_ = false;  // format 1 or 2: inputs as the stick fields
  ReplayWriterOptions options_;
  std::vector<uint8_t> buffer_;
  std::chrono::steady_clock::time_point last_flush_;
  uint64_t bytes_flushed_ = 0;
  Tick last_tick_ = kNoTick;
  Tick last_keyframe_tick_ = kNoTick - 1;
  bool finished_ = false;
  Status failure_;
};

}  // namespace rwd::replay
