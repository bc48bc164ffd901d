// SPDX-License-Identifier: MIT
#pragma once
// Streaming replay reader. It trusts nothing: every frame's length is bounded,
// every payload's hash is checked, and records must follow each other as the
// writer wrote them (ticks contiguous from 0, keyframes after their tick, one
// end record last). Errors name the byte offset, the record number (the
// header is record 0) and the last good tick.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/core/tick.h"
#include "rewind/v1/replay.pb.h"

namespace rwd::replay {

/// Where a read through a replay stands. Everything but kReading is final.
enum class ReadState : uint8_t {
  kReading,      ///< more records may follow
  kComplete,     ///< read to the end record, and nothing follows it
  kIncomplete,   ///< the file stops on a frame boundary without an end record
  kTorn,         ///< the file stops inside a frame: the last write was cut short
  kCorrupt,      ///< a frame fails its hash, does not parse, or breaks the order
  kUnsupported,  ///< a newer format: the header is read, the records are not
  kIoError,      ///< the operating system refused a read
};

/// "complete", "incomplete", "torn", ...: for reports and JSON.
const char* read_state_name(ReadState state);

/// Reads a replay file record by record, checking framing, hashes and order.
class ReplayReader {
 public:
  /// Opens `path` and reads the magic and the header record. kIo when the
  /// file cannot be read, kCorrupt/kInvalidArgument when it is no usable
  /// replay. A header of a newer format (with valid game and player count)
  /// opens, so tools can show it; next() then refuses with kUnsupported.
  static Result<ReplayReader> open(const std::string& path);
  /// Same over bytes in memory (fuzzing, tests, network uploads).
  static Result<ReplayReader> from_bytes(std::span<const uint8_t> bytes);

  ReplayReader(ReplayReader&&) noexcept;
  ReplayReader& operator=(ReplayReader&&) noexcept;
  ReplayReader(const ReplayReader&) = delete;
  ReplayReader& operator=(const ReplayReader&) = delete;
  ~ReplayReader();

  /// The header record, already validated.
  const v1::ReplayHeader& header() const { return header_; }

  /// The next record after the header (tick, keyframe or end); nullopt at
  /// the end of the file when the file ends on a frame boundary or after
  /// the end record. After an error every further call returns that error.
  Result<std::optional<v1::ReplayRecord>> next();

  /// Byte offset of the next frame (the end of the last good one).
  uint64_t offset() const { return offset_; }
  /// Records read so far, header included.
  uint64_t records_read() const { return records_; }
  /// The last tick record read, kNoTick before the first.
  Tick last_tick() const { return last_tick_; }
  /// True once the end record has been read.
  bool ended() const { return ended_; }
  /// The error that stopped the reader, if any.
  const Status& error() const { return failure_; }
  /// How far reading got: kReading until next() has returned the end of
  /// the file or an error. A frame that runs past the end of the file is
  /// kTorn (an error from next(), with kCorrupt, saying where), unless a
  /// prefix of what is there matches the frame's hash: then its length
  /// field is damaged and the file is kCorrupt.
  ReadState state() const;

 private:
  struct Source;
  explicit ReplayReader(std::unique_ptr<Source> source);
  static Result<ReplayReader> start(std::unique_ptr<Source> source);
  Result<std::optional<v1::ReplayRecord>> read_frame();
  Status check_order(const v1::ReplayRecord& record) const;
  std::string where(uint64_t frame_offset) const;
  Status fail(ErrorCode code, const std::string& message);

  std::unique_ptr<Source> source_;
  v1::ReplayHeader header_;
  uint64_t offset_ = 0;
  uint64_t records_ = 0;
  Tick last_tick_ = kNoTick;
  Tick last_keyframe_tick_ = kNoTick - 1;
  bool ended_ = false;
  bool at_eof_ = false;
  bool torn_ = false;
  bool newer_format_ = false;
  Status failure_;
  std::vector<uint8_t> payload_;
};

}  // namespace rwd::replay
