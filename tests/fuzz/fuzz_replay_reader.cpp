// SPDX-License-Identifier: MIT
// Fuzz entry for the replay reader: arbitrary bytes must give records or a
// Status, never a crash, and whatever reads cleanly must survive being
// framed again and re-read unchanged.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"

namespace {

using rwd::Result;
using rwd::replay::ReplayReader;
using rwd::v1::ReplayRecord;

// Reads every record after the header; false when the reader reported an
// error. Traps when the reader breaks one of its own promises.
bool read_all(ReplayReader& reader, size_t size, std::vector<ReplayRecord>& records) {
  while (true) {
    Result<std::optional<ReplayRecord>> next = reader.next();
    if (reader.offset() > size) __builtin_trap();
    if (!next.ok()) {
      if (next.status().message().empty()) __builtin_trap();
      // Errors are sticky.
      if (reader.next().ok()) __builtin_trap();
      return false;
    }
    if (!next->has_value()) return true;
    records.push_back(std::move(**next));
  }
}

// Rewrites every complete frame's hash to match its payload. Random bytes
// almost never carry a valid XXH3, so without this the fuzzer would stop at
// the hash check and never reach the parser and the ordering rules.
void fix_hashes(std::vector<uint8_t>& bytes) {
  size_t at = rwd::replay::kMagic.size();
  while (at + rwd::replay::kFrameHeaderBytes <= bytes.size()) {
    const uint32_t len = uint32_t{bytes[at]} | uint32_t{bytes[at + 1]} << 8 |
                         uint32_t{bytes[at + 2]} << 16 | uint32_t{bytes[at + 3]} << 24;
    const size_t payload = at + rwd::replay::kFrameHeaderBytes;
    if (len > bytes.size() - payload) return;
    const uint64_t hash = rwd::replay::payload_hash({bytes.data() + payload, len});
    for (int i = 0; i < 8; ++i) bytes[at + 4 + i] = static_cast<uint8_t>(hash >> (8 * i));
    at = payload + len;
  }
}

}  // namespace

/// The first byte picks the mode (odd: repair frame hashes first); the rest
/// is the file.
int fuzz_replay_reader_one(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::vector<uint8_t> file(data + 1, data + size);
  if (data[0] & 1u) fix_hashes(file);
  size = file.size();
  Result<ReplayReader> reader = ReplayReader::from_bytes(file);
  if (!reader.ok()) {
    if (reader.status().message().empty()) __builtin_trap();
    return 0;
  }
  std::vector<ReplayRecord> records;
  if (!read_all(*reader, size, records)) return 0;

  // Round trip: frame the header and records again and read them back.
  std::vector<uint8_t> bytes(rwd::replay::kMagic.begin(), rwd::replay::kMagic.end());
  ReplayRecord header;
  *header.mutable_header() = reader->header();
  if (!rwd::replay::append_frame(header, bytes).ok()) __builtin_trap();
  for (const ReplayRecord& r : records) {
    if (!rwd::replay::append_frame(r, bytes).ok()) __builtin_trap();
  }
  Result<ReplayReader> again = ReplayReader::from_bytes(bytes);
  if (!again.ok()) __builtin_trap();
  std::vector<ReplayRecord> reread;
  if (!read_all(*again, bytes.size(), reread)) __builtin_trap();
  if (reread.size() != records.size()) __builtin_trap();
  for (size_t i = 0; i < records.size(); ++i) {
    if (reread[i].SerializeAsString() != records[i].SerializeAsString()) __builtin_trap();
  }
  if (again->ended() != reader->ended()) __builtin_trap();
  return 0;
}
