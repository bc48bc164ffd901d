// SPDX-License-Identifier: MIT
#pragma once
// The datagrams a ClientProtocol has made and its caller has not yet taken:
// a ring of buffers that keep their capacity, so a steady stream of sends
// allocates nothing once every slot has held its largest datagram.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace rwd::client {

class DatagramQueue {
 public:
  /// At most `max_datagrams` (>= 1) wait at once.
  explicit DatagramQueue(size_t max_datagrams) : slots_(max_datagrams == 0 ? 1 : max_datagrams) {}

  /// Copies `bytes` in; false (nothing queued) when the queue is full.
  bool push(std::span<const uint8_t> bytes) {
    if (count_ == slots_.size()) return false;
    std::vector<uint8_t>& slot = slots_[(head_ + count_) % slots_.size()];
    slot.assign(bytes.begin(), bytes.end());
    ++count_;
    return true;
  }

  /// Removes the oldest datagram and returns its bytes, which stay valid
  /// until its slot is reused: no sooner than max_datagrams - 1 push()es on.
  std::optional<std::span<const uint8_t>> pop() {
    if (count_ == 0) return std::nullopt;
    const std::vector<uint8_t>& slot = slots_[head_];
    head_ = (head_ + 1) % slots_.size();
    --count_;
    return std::span<const uint8_t>(slot);
  }

  size_t size() const { return count_; }

 private:
  std::vector<std::vector<uint8_t>> slots_;
  size_t head_ = 0;
  size_t count_ = 0;
};

}  // namespace rwd::client
