// SPDX-License-Identifier: MIT
#include "rewind/replay/replay_writer.h"
#include "rewind/proto/input_wire.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "rewind/core/stick_input.h"
#include "rewind/replay/replay_format.h"

namespace rwd::replay {
namespace {

Status os_error(const std::string& what, const std::string& path, int err) {
  return Status::Error(ErrorCode::kIo, what + " " + path + ": " + std::strerror(err));
}

std::chrono::steady_clock::time_point now_from(const ReplayWriterOptions& options) {
  return options.clock ? options.clock() : std::chrono::steady_clock::now();
}

}  // namespace

Result<ReplayWriter> ReplayWriter::open(const std::string& path, const v1::ReplayHeader& header,
                                        ReplayWriterOptions options) {
  v1::ReplayHeader stamped = header;
  if (stamped.format_version() == 0) stamped.set_format_version(kFormatVersion);
  if (Status s = validate_header(stamped); !s.ok()) {
    // A newer format is readable as a header only; this build cannot write one.
    return Status::Error(
        s.code() == ErrorCode::kUnsupported ? ErrorCode::kInvalidArgument : s.code(), s.message());
  }

  struct stat st {};
  if (!options.overwrite && ::stat(path.c_str(), &st) == 0 && st.st_size > 0) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "replay file " + path + " already exists and is not empty");
  }
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return os_error("cannot create replay file", path, errno);

  ReplayWriter writer(path, fd, stamped, std::move(options));
  writer.buffer_.assign(kMagic.begin(), kMagic.end());
  v1::ReplayRecord record;
  *record.mutable_header() = stamped;
  if (Status s = append_frame(record, writer.buffer_); !s.ok()) return s;
  // The header reaches the OS at once: a match that dies in its first second
  // still leaves a file that names its game and seed.
  if (Status s = writer.flush(); !s.ok()) return s;
  return writer;
}

ReplayWriter::ReplayWriter(std::string path, int fd, const v1::ReplayHeader& header,
                           ReplayWriterOptions options)
    : path_(std::move(path)),
      fd_(fd),
      player_count_(header.player_count()),
      stick_inputs_(header.format_version() < 3),
      options_(std::move(options)),
      last_flush_(now_from(options_)) {}

ReplayWriter::ReplayWriter(ReplayWriter&& other) noexcept
    : path_(std::move(other.path_)),
      fd_(std::exchange(other.fd_, -1)),
      player_count_(other.player_count_),
      stick_inputs_(other.stick_inputs_),
      options_(std::move(other.options_)),
      buffer_(std::move(other.buffer_)),
      last_flush_(other.last_flush_),
      bytes_flushed_(other.bytes_flushed_),
      last_tick_(other.last_tick_),
      last_keyframe_tick_(other.last_keyframe_tick_),
      finished_(other.finished_),
      failure_(std::move(other.failure_)) {
  other.buffer_.clear();
}

ReplayWriter& ReplayWriter::operator=(ReplayWriter&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) {
      (void)flush();
      close_fd();
    }
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    player_count_ = other.player_count_;
    stick_inputs_ = other.stick_inputs_;
    options_ = std::move(other.options_);
    buffer_ = std::move(other.buffer_);
    other.buffer_.clear();
    last_flush_ = other.last_flush_;
    bytes_flushed_ = other.bytes_flushed_;
    last_tick_ = other.last_tick_;
    last_keyframe_tick_ = other.last_keyframe_tick_;
    finished_ = other.finished_;
    failure_ = std::move(other.failure_);
  }
  return *this;
}

ReplayWriter::~ReplayWriter() {
  if (fd_ >= 0) {
    // Best effort: a destructor cannot report, and whatever reaches the file
    // is still a verifiable prefix.
    (void)flush();
    close_fd();
  }
}

void ReplayWriter::close_fd() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

Status ReplayWriter::usable() const {
  if (!failure_.ok()) {
    return Status::Error(failure_.code(), "replay writer failed earlier: " + failure_.message());
  }
  if (finished_ || fd_ < 0) {
    return Status::Error(ErrorCode::kInvalidArgument, "replay " + path_ + " is already finished");
  }
  return Status::Ok();
}

Status ReplayWriter::append_tick(Tick tick, std::span<const rwd::PlayerInput> inputs,
                                 uint64_t substituted_mask, uint64_t checksum) {
  if (Status s = usable(); !s.ok()) return s;
  if (tick != last_tick_ + 1) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "replay tick " + std::to_string(tick) + " appended " +
                             describe_last_tick(last_tick_) + "; expected tick " +
                             std::to_string(last_tick_ + 1));
  }
  if (inputs.size() != player_count_) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "replay tick " + std::to_string(tick) + " has " +
                             std::to_string(inputs.size()) + " inputs for " +
                             std::to_string(player_count_) + " players");
  }
  if (player_count_ < 64 && (substituted_mask >> player_count_) != 0) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "replay tick " + std::to_string(tick) +
                             " marks substituted inputs for players beyond " +
                             std::to_string(player_count_));
  }
  if (stick_inputs_) {
    for (const rwd::PlayerInput& input : inputs) {
      if (!(rwd::PlayerInput::of(input.as<rwd::StickInput>()) == input)) {
        return Status::Error(ErrorCode::kInvalidArgument,
                             "replay tick " + std::to_string(tick) +
                                 ": an input that is not a stick input, in a format " +
                                 std::to_string(kFormatVersion - 1) + " or older file");
      }
    }
  }
  v1::ReplayRecord record;
  v1::ReplayTick* out = record.mutable_tick();
  out->set_tick(tick);
  for (const rwd::PlayerInput& input : inputs) {
    v1::Input* wire = out->add_inputs();
    if (!stick_inputs_) {
      *wire = proto::to_wire(input);
      continue;
    }
    // Formats 1 and 2 stored the stick fields (copies of old files).
    const auto stick = input.as<rwd::StickInput>();
    wire->set_axis_x(stick.axis_x);
    wire->set_axis_y(stick.axis_y);
    wire->set_buttons(stick.buttons);
  }
  out->set_substituted_mask(substituted_mask);
  out->set_checksum(checksum);
  if (Status s = append_frame(record, buffer_); !s.ok()) return s;
  last_tick_ = tick;
  return maybe_flush();
}

Status ReplayWriter::append_keyframe(Tick tick, std::span<const uint8_t> serialized_state) {
  if (Status s = usable(); !s.ok()) return s;
  if (tick != last_tick_ || tick == last_keyframe_tick_) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "replay keyframe for tick " + std::to_string(tick) +
                             " must hold the state after the last appended tick (" +
                             std::to_string(last_tick_) + ") and appear once");
  }
  v1::ReplayRecord record;
  v1::ReplayKeyframe* out = record.mutable_keyframe();
  out->set_tick(tick);
  out->set_state(serialized_state.data(), serialized_state.size());
  if (Status s = append_frame(record, buffer_); !s.ok()) return s;
  last_keyframe_tick_ = tick;
  return flush();
}

Status ReplayWriter::finish(Tick last_final_tick, std::string_view reason) {
  if (Status s = usable(); !s.ok()) return s;
  if (last_final_tick != last_tick_) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "replay finish names last final tick " + std::to_string(last_final_tick) +
                             " but the last appended tick is " + std::to_string(last_tick_));
  }
  v1::ReplayRecord record;
  record.mutable_end()->set_last_final_tick(last_final_tick);
  record.mutable_end()->set_reason(std::string(reason));
  if (Status s = append_frame(record, buffer_); !s.ok()) return s;
  if (Status s = flush(); !s.ok()) return s;
  // Character devices and pipes cannot be synced; that is not a lost record.
  if (::fsync(fd_) != 0 && errno != EINVAL && errno != EROFS) {
    failure_ = os_error("cannot fsync replay file", path_, errno);
    close_fd();
    return failure_;
  }
  finished_ = true;
  if (::close(fd_) != 0) {
    fd_ = -1;
    failure_ = os_error("cannot close replay file", path_, errno);
    return failure_;
  }
  fd_ = -1;
  return Status::Ok();
}

Status ReplayWriter::maybe_flush() {
  if (buffer_.size() >= options_.flush_bytes ||
      now_from(options_) - last_flush_ >= options_.flush_interval) {
    return flush();
  }
  return Status::Ok();
}

Status ReplayWriter::flush_if_due() {
  if (Status s = usable(); !s.ok()) return s;
  return maybe_flush();
}

Status ReplayWriter::flush() {
  if (!failure_.ok()) return usable();
  if (fd_ < 0) return usable();
  size_t done = 0;
  while (done < buffer_.size()) {
    const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<ptrdiff_t>(done));
      bytes_flushed_ += done;
      failure_ = os_error("cannot write replay file", path_, err);
      return failure_;
    }
    done += static_cast<size_t>(n);
  }
  bytes_flushed_ += done;
  buffer_.clear();
  last_flush_ = now_from(options_);
  return Status::Ok();
}

}  // namespace rwd::replay
