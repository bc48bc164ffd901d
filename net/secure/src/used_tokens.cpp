// SPDX-License-Identifier: MIT
#include "rewind/net/used_tokens.h"

#include <cstring>

namespace rwd::net {

size_t UsedTokens::MacHash::operator()(const TokenMac& mac) const {
  uint64_t h = 0;
  std::memcpy(&h, mac.data(), sizeof h);
  return static_cast<size_t>(h);
}

bool UsedTokens::used(const TokenMac& mac, int64_t now_unix_s) const {
  const auto it = expiry_.find(mac);
  return it != expiry_.end() && now_unix_s < it->second;
}

UsedTokens::Outcome UsedTokens::record(const TokenMac& mac, int64_t expiry_unix_s,
                                       int64_t now_unix_s) {
  if (used(mac, now_unix_s)) return Outcome::kAlreadyUsed;
  // An expired entry for the same MAC is simply renewed below (the token
  // itself is refused as expired before it gets here).
  if (expiry_.size() >= capacity_ && expiry_.find(mac) == expiry_.end()) prune(now_unix_s);
  if (expiry_.size() >= capacity_ && expiry_.find(mac) == expiry_.end()) return Outcome::kFull;
  expiry_[mac] = expiry_unix_s;
  return Outcome::kRecorded;
}

void UsedTokens::prune(int64_t now_unix_s) {
  std::erase_if(expiry_, [now_unix_s](const auto& entry) { return now_unix_s >= entry.second; });
}

}  // namespace rwd::net
