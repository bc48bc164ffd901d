// SPDX-License-Identifier: MIT
// Fuzz entry for the replay reader: arbitrary bytes must give records or a
// Status, never a crash, and whatever reads cleanly must survive being
// framed again and re-read unchanged.
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <span>
#include <vector>

#include "fuzz_entries.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"

namespace {

using rwd::Result;
using rwd::replay::ReplayReader;
using rwd::v1::ReplayRecord;

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_replay_reader: invariant broken: %s\n", what);
  std::abort();
}

// A torn frame really runs past the end of the input: either its 12-byte
// frame header or the payload its length field announces.
void check_torn(const ReplayReader& reader, const std::vector<uint8_t>& file) {
  const size_t at = reader.offset();
  const size_t left = file.size() - at;
  if (left < rwd::replay::kFrameHeaderBytes) return;
  const uint32_t len = uint32_t{file[at]} | uint32_t{file[at + 1]} << 8 |
                       uint32_t{file[at + 2]} << 16 | uint32_t{file[at + 3]} << 24;
  if (len <= left - rwd::replay::kFrameHeaderBytes) invariant_broken("torn frame that fits");
}

// Reads every record after the header; false when the reader reported an
// error. The read state must agree with how reading ended.
bool read_all(ReplayReader& reader, const std::vector<uint8_t>& file,
              std::vector<ReplayRecord>& records) {
  while (true) {
    if (reader.state() != rwd::replay::ReadState::kReading) {
      invariant_broken("read state final before the end");
    }
    Result<std::optional<ReplayRecord>> next = reader.next();
    if (reader.offset() > file.size()) invariant_broken("offset past the end of the input");
    if (!next.ok()) {
      if (next.status().message().empty()) invariant_broken("error without message");
      if (reader.next().ok()) invariant_broken("error did not stick");
      switch (reader.state()) {
        case rwd::replay::ReadState::kTorn:
          check_torn(reader, file);
          break;
        case rwd::replay::ReadState::kUnsupported:
          if (reader.header().format_version() <= rwd::replay::kFormatVersion) {
            invariant_broken("unsupported records in a readable format");
          }
          break;
        case rwd::replay::ReadState::kCorrupt:
          break;
        default:
          invariant_broken("error with a read state that is not an error");
      }
      return false;
    }
    if (!next->has_value()) {
      const rwd::replay::ReadState want =
          reader.ended() ? rwd::replay::ReadState::kComplete : rwd::replay::ReadState::kIncomplete;
      if (reader.state() != want) invariant_broken("clean end with the wrong read state");
      return true;
    }
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

int fuzz_replay_reader_one(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::vector<uint8_t> file(data + 1, data + size);
  if (data[0] & 1u) fix_hashes(file);
  Result<ReplayReader> reader = ReplayReader::from_bytes(file);
  if (!reader.ok()) {
    if (reader.status().message().empty()) invariant_broken("open error without message");
    return 0;
  }
  std::vector<ReplayRecord> records;
  if (!read_all(*reader, file, records)) return 0;

  // Round trip: frame the header and records again and read them back.
  std::vector<uint8_t> bytes(rwd::replay::kMagic.begin(), rwd::replay::kMagic.end());
  ReplayRecord header;
  *header.mutable_header() = reader->header();
  if (!rwd::replay::append_frame(header, bytes).ok()) invariant_broken("header does not frame");
  for (const ReplayRecord& r : records) {
    if (!rwd::replay::append_frame(r, bytes).ok()) invariant_broken("record does not frame");
  }
  Result<ReplayReader> again = ReplayReader::from_bytes(bytes);
  if (!again.ok()) invariant_broken("re-framed header does not read");
  std::vector<ReplayRecord> reread;
  if (!read_all(*again, bytes, reread)) invariant_broken("re-framed records do not read");
  if (reread.size() != records.size()) invariant_broken("record count changed");
  for (size_t i = 0; i < records.size(); ++i) {
    if (reread[i].SerializeAsString() != records[i].SerializeAsString()) {
      invariant_broken("record changed in the round trip");
    }
  }
  if (again->ended() != reader->ended()) invariant_broken("end record lost");
  return 0;
}
