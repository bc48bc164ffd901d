// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace rwd {

/// Why an operation refused its input. Every API that takes outside data
/// answers with a Status instead of throwing, and leaves state untouched on
/// error.
enum class ErrorCode : uint8_t {
  kOk = 0,
  kInvalidArgument,  ///< NaN, inf, out of range, degenerate
  kNotFound,         ///< unknown or stale handle
  kCapacity,         ///< a fixed limit would be exceeded
  kCorrupt,          ///< malformed bytes (file, datagram, snapshot)
  kUnsupported,      ///< a valid request this build cannot honour
  kIo,               ///< the operating system refused
};

/// Success, or an error code with a human-readable message.
class [[nodiscard]] Status {
 public:
  Status() = default;
  static Status Ok() { return {}; }
  static Status Error(ErrorCode code, std::string message) {
    Status s;
    s.code_ = code;
    s.message_ = std::move(message);
    return s;
  }
  bool ok() const { return code_ == ErrorCode::kOk; }
  ErrorCode code() const { return code_; }
  const std::string& message() const { return message_; }

 private:
  ErrorCode code_ = ErrorCode::kOk;
  std::string message_;
};

/// Thrown when a Result that holds an error is read as a value: a bug in
/// the caller, who must check ok() first. what() carries the error's
/// message.
class BadResultAccess : public std::logic_error {
 public:
  explicit BadResultAccess(const Status& status)
      : std::logic_error("read the value of a failed Result: " + status.message()) {}
};

/// A value or the Status explaining why there is none. Check ok() before
/// reading the value: reading a failed Result throws BadResultAccess
/// instead of reading nothing. An error Status must not be Ok.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}          // NOLINT: implicit by design
  Result(Status status) : status_(std::move(status)) {}  // NOLINT
  bool ok() const { return value_.has_value(); }
  const Status& status() const { return status_; }
  T& value() { return checked(); }
  const T& value() const { return checked(); }
  T* operator->() { return &checked(); }
  const T* operator->() const { return &checked(); }
  T& operator*() { return checked(); }
  const T& operator*() const { return checked(); }

 private:
  T& checked() {
    if (!value_) throw BadResultAccess(status_);
    return *value_;
  }
  const T& checked() const {
    if (!value_) throw BadResultAccess(status_);
    return *value_;
  }

  std::optional<T> value_;
  Status status_;
};

}  // namespace rwd
