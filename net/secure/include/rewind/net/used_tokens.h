// SPDX-License-Identifier: MIT
#pragma once
// The connect tokens a server has accepted, remembered until they expire,
// so that each connects once (as netcode.io's server remembers token
// MACs): a copy of a token, keys included, cannot take a slot back from
// the client that used it, and a client that comes back needs a fresh
// token from its backend. Memory is bounded: expired entries are pruned,
// and when the log is full of unexpired ones a new token is refused rather
// than an unexpired one forgotten (forgetting would let its copies in).
#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>

#include "rewind/net/secure_channel.h"

namespace rwd::net {

class UsedTokens {
 public:
  /// Enough for every slot of a 64-seat match to reconnect dozens of times
  /// within a token's lifetime; about 40 bytes each.
  static constexpr size_t kDefaultCapacity = 4096;

  explicit UsedTokens(size_t capacity = kDefaultCapacity) : capacity_(capacity) {}

  /// Whether `mac` was recorded and has not expired at `now_unix_s`.
  bool used(const TokenMac& mac, int64_t now_unix_s) const;

  enum class Outcome : uint8_t {
    kRecorded,     ///< the token is now used
    kAlreadyUsed,  ///< it was used before: refuse the connection
    kFull,         ///< no room even after pruning: refuse the connection
  };
  /// Records a token at its first connection; valid until `expiry_unix_s`.
  Outcome record(const TokenMac& mac, int64_t expiry_unix_s, int64_t now_unix_s);

  size_t size() const { return expiry_.size(); }
  size_t capacity() const { return capacity_; }

 private:
  struct MacHash {
    // The MAC is a keyed authenticator: its bytes are already uniform.
    size_t operator()(const TokenMac& mac) const;
  };
  void prune(int64_t now_unix_s);

  size_t capacity_;
  std::unordered_map<TokenMac, int64_t, MacHash> expiry_;
};

}  // namespace rwd::net
