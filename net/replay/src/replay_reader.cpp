// SPDX-License-Identifier: MIT
#include "rewind/replay/replay_reader.h"
#include "rewind/proto/input_wire.h"

#include <cerrno>
#include <cstring>
#include <utility>

#include <google/protobuf/stubs/logging.h>

#include "rewind/replay/replay_format.h"

namespace rwd::replay {

// Where the bytes come from: a FILE* or a copy in memory. Reads return how
// many bytes were available so truncation can say "need N, have M".
struct ReplayReader::Source {
  std::FILE* file = nullptr;
  std::vector<uint8_t> memory;
  size_t memory_pos = 0;
  std::string name;

  ~Source() {
    if (file != nullptr) std::fclose(file);
  }

  // Reads up to `size` bytes; kIo only for an operating-system error.
  Result<size_t> read(uint8_t* out, size_t size) {
    if (file == nullptr) {
      const size_t n = std::min(size, memory.size() - memory_pos);
      if (n > 0) std::memcpy(out, memory.data() + memory_pos, n);
      memory_pos += n;
      return n;
    }
    const size_t n = std::fread(out, 1, size, file);
    if (n < size && std::ferror(file)) {
      return Status::Error(ErrorCode::kIo, "cannot read " + name + ": " + std::strerror(errno));
    }
    return n;
  }
};

const char* read_state_name(ReadState state) {
  switch (state) {
    case ReadState::kReading:
      return "reading";
    case ReadState::kComplete:
      return "complete";
    case ReadState::kIncomplete:
      return "incomplete";
    case ReadState::kTorn:
      return "torn";
    case ReadState::kCorrupt:
      return "corrupt";
    case ReadState::kUnsupported:
      return "unsupported";
    case ReadState::kIoError:
      return "io_error";
  }
  return "unknown";
}

ReadState ReplayReader::state() const {
  if (!failure_.ok()) {
    if (torn_) return ReadState::kTorn;
    if (failure_.code() == ErrorCode::kUnsupported) return ReadState::kUnsupported;
    if (failure_.code() == ErrorCode::kIo) return ReadState::kIoError;
    return ReadState::kCorrupt;
  }
  if (at_eof_) return ended_ ? ReadState::kComplete : ReadState::kIncomplete;
  return ReadState::kReading;
}

Result<ReplayReader> ReplayReader::open(const std::string& path) {
  auto source = std::make_unique<Source>();
  source->name = path;
  source->file = std::fopen(path.c_str(), "rb");
  if (source->file == nullptr) {
    return Status::Error(ErrorCode::kIo,
                         "cannot open replay " + path + ": " + std::strerror(errno));
  }
  return start(std::move(source));
}

Result<ReplayReader> ReplayReader::from_bytes(std::span<const uint8_t> bytes) {
  auto source = std::make_unique<Source>();
  source->name = "replay bytes";
  source->memory.assign(bytes.begin(), bytes.end());
  return start(std::move(source));
}

ReplayReader::ReplayReader(std::unique_ptr<Source> source) : source_(std::move(source)) {}
ReplayReader::ReplayReader(ReplayReader&&) noexcept = default;
ReplayReader& ReplayReader::operator=(ReplayReader&&) noexcept = default;
ReplayReader::~ReplayReader() = default;

Result<ReplayReader> ReplayReader::start(std::unique_ptr<Source> source) {
  ReplayReader reader(std::move(source));
  uint8_t magic[kMagic.size()];
  Result<size_t> got = reader.source_->read(magic, sizeof magic);
  if (!got.ok()) return got.status();
  if (*got < sizeof magic) {
    return Status::Error(ErrorCode::kCorrupt, "bad magic: file has " + std::to_string(*got) +
                                                  " bytes, a replay starts with the " +
                                                  std::to_string(kMagic.size()) +
                                                  " bytes \"RWRPLY01\"");
  }
  if (std::memcmp(magic, kMagic.data(), kMagic.size()) != 0) {
    return Status::Error(ErrorCode::kCorrupt,
                         "bad magic at byte 0: not a replay file (expected \"RWRPLY01\")");
  }
  reader.offset_ = kMagic.size();

  const uint64_t header_offset = reader.offset_;
  Result<std::optional<v1::ReplayRecord>> first = reader.read_frame();
  if (!first.ok()) return first.status();
  if (!first->has_value() || !(*first)->has_header()) {
    return Status::Error(ErrorCode::kCorrupt,
                         "header missing at byte " + std::to_string(header_offset) +
                             " (record 0): the first record must be the replay header");
  }
  if (Status s = validate_header((*first)->header()); !s.ok()) {
    if (s.code() != ErrorCode::kUnsupported) {
      return Status::Error(s.code(), "bad header at byte " + std::to_string(header_offset) +
                                         " (record 0): " + s.message());
    }
    reader.newer_format_ = true;
  }
  reader.header_ = (*first)->header();
  return reader;
}

std::string ReplayReader::where(uint64_t frame_offset) const {
  return "byte " + std::to_string(frame_offset) + " (record " + std::to_string(records_) + ", " +
         describe_last_tick(last_tick_) + ")";
}

Status ReplayReader::fail(ErrorCode code, const std::string& message) {
  failure_ = Status::Error(code, message);
  return failure_;
}

Result<std::optional<v1::ReplayRecord>> ReplayReader::read_frame() {
  const uint64_t frame_offset = offset_;
  uint8_t head[kFrameHeaderBytes];
  Result<size_t> got = source_->read(head, sizeof head);
  if (!got.ok()) return fail(ErrorCode::kIo, got.status().message());
  if (*got == 0) {
    at_eof_ = true;
    return std::optional<v1::ReplayRecord>();
  }
  if (*got < sizeof head) {
    torn_ = true;
    return fail(ErrorCode::kCorrupt, "truncated frame at " + where(frame_offset) + ": need " +
                                         std::to_string(kFrameHeaderBytes) + " bytes, have " +
                                         std::to_string(*got));
  }
  uint32_t length = 0;
  uint64_t hash = 0;
  for (int i = 0; i < 4; ++i) length |= uint32_t{head[i]} << (8 * i);
  for (int i = 0; i < 8; ++i) hash |= uint64_t{head[4 + i]} << (8 * i);
  if (length > kMaxRecordBytes) {
    return fail(ErrorCode::kCorrupt, "length " + std::to_string(length) + " exceeds limit " +
                                         std::to_string(kMaxRecordBytes) + " at " +
                                         where(frame_offset));
  }
  payload_.resize(length);
  got = source_->read(payload_.data(), length);
  if (!got.ok()) return fail(ErrorCode::kIo, got.status().message());
  if (*got < length) {
    if (std::optional<size_t> real = prefix_with_hash({payload_.data(), *got}, hash)) {
      return fail(ErrorCode::kCorrupt,
                  "damaged length at " + where(frame_offset) + ": the frame claims " +
                      std::to_string(length) + " bytes but its hash matches its first " +
                      std::to_string(*real) + " (a damaged length field, not a cut-short write)");
    }
    torn_ = true;
    return fail(ErrorCode::kCorrupt, "truncated frame at " + where(frame_offset) + ": need " +
                                         std::to_string(kFrameHeaderBytes + length) +
                                         " bytes, have " +
                                         std::to_string(kFrameHeaderBytes + *got));
  }
  if (payload_hash(payload_) != hash) {
    return fail(ErrorCode::kCorrupt, "hash mismatch at " + where(frame_offset) +
                                         ": the record's bytes are not the ones written");
  }
  v1::ReplayRecord record;
  // A corrupt string field makes protobuf log to stderr; the Status below
  // already says it, with the location.
  google::protobuf::LogSilencer quiet;
  if (!record.ParseFromArray(payload_.data(), static_cast<int>(length))) {
    return fail(ErrorCode::kCorrupt, "unparsable record at " + where(frame_offset));
  }
  if (record.record_case() == v1::ReplayRecord::RECORD_NOT_SET) {
    return fail(ErrorCode::kCorrupt, "record of unknown type at " + where(frame_offset));
  }
  if (records_ > 0) {
    if (Status s = check_order(record); !s.ok()) {
      return fail(s.code(), s.message() + " at " + where(frame_offset));
    }
  }
  offset_ += kFrameHeaderBytes + length;
  ++records_;
  return std::optional<v1::ReplayRecord>(std::move(record));
}

Status ReplayReader::check_order(const v1::ReplayRecord& record) const {
  const uint32_t players = header_.player_count();
  switch (record.record_case()) {
    case v1::ReplayRecord::kHeader:
      return Status::Error(ErrorCode::kCorrupt, "second header");
    case v1::ReplayRecord::kTick: {
      const v1::ReplayTick& t = record.tick();
      if (t.tick() != last_tick_ + 1) {
        const std::string expected =
            last_tick_ == kNoTick ? "first tick is " + std::to_string(t.tick()) + ", expected 0"
                                  : "tick " + std::to_string(t.tick()) + " follows tick " +
                                        std::to_string(last_tick_);
        return Status::Error(ErrorCode::kCorrupt, expected);
      }
      if (static_cast<uint32_t>(t.inputs_size()) != players) {
        return Status::Error(ErrorCode::kCorrupt, "tick " + std::to_string(t.tick()) + " has " +
                                                      std::to_string(t.inputs_size()) +
                                                      " inputs for " + std::to_string(players) +
                                                      " players");
      }
      for (const v1::Input& input : t.inputs()) {
        Result<rwd::PlayerInput> converted = proto::from_wire(input);
        if (!converted.ok()) {
          return Status::Error(ErrorCode::kCorrupt, "tick " + std::to_string(t.tick()) + ": " +
                                                        converted.status().message());
        }
      }
      if (players < 64 && (t.substituted_mask() >> players) != 0) {
        return Status::Error(ErrorCode::kCorrupt, "tick " + std::to_string(t.tick()) +
                                                      " marks substituted inputs beyond player " +
                                                      std::to_string(players - 1));
      }
      return Status::Ok();
    }
    case v1::ReplayRecord::kKeyframe: {
      const Tick tick = record.keyframe().tick();
      if (tick != last_tick_ || tick == last_keyframe_tick_) {
        return Status::Error(ErrorCode::kCorrupt,
                             "keyframe for tick " + std::to_string(tick) +
                                 " does not hold the state after the last tick (" +
                                 std::to_string(last_tick_) + ")");
      }
      return Status::Ok();
    }
    case v1::ReplayRecord::kEnd:
      if (record.end().last_final_tick() != last_tick_) {
        return Status::Error(ErrorCode::kCorrupt,
                             "end record names last final tick " +
                                 std::to_string(record.end().last_final_tick()) +
                                 " but the last tick recorded is " + std::to_string(last_tick_));
      }
      return Status::Ok();
    case v1::ReplayRecord::RECORD_NOT_SET:
      break;
  }
  return Status::Error(ErrorCode::kCorrupt, "record of unknown type");
}

Result<std::optional<v1::ReplayRecord>> ReplayReader::next() {
  if (!failure_.ok()) return failure_;
  if (at_eof_) return std::optional<v1::ReplayRecord>();
  if (newer_format_) {
    return fail(ErrorCode::kUnsupported,
                "records of replay format version " + std::to_string(header_.format_version()) +
                    " are not read by this build (it reads " + readable_formats() + ")");
  }
  if (ended_) {
    // The end record is the last thing a writer writes; anything after it
    // was appended by someone else.
    uint8_t extra[1];
    Result<size_t> got = source_->read(extra, 1);
    if (!got.ok()) return fail(ErrorCode::kIo, got.status().message());
    if (*got != 0) {
      return fail(ErrorCode::kCorrupt, "data after the end record at " + where(offset_));
    }
    at_eof_ = true;
    return std::optional<v1::ReplayRecord>();
  }
  Result<std::optional<v1::ReplayRecord>> record = read_frame();
  if (!record.ok() || !record->has_value()) return record;
  const v1::ReplayRecord& r = **record;
  if (r.has_tick()) last_tick_ = r.tick().tick();
  if (r.has_keyframe()) last_keyframe_tick_ = r.keyframe().tick();
  if (r.has_end()) ended_ = true;
  return record;
}

}  // namespace rwd::replay
