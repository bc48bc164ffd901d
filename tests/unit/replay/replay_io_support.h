// SPDX-License-Identifier: MIT
#pragma once
// Helpers of the replay file-format tests (writer, reader, summary): test
// headers and inputs, temporary files, and a builder of hand-made files.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "rewind/core/stick_input.h"
#include "rewind/proto/input_wire.h"
#include "rewind/replay/replay_format.h"
#include "rewind/replay/replay_reader.h"
#include "rewind/replay/replay_rewrite.h"
#include "rewind/replay/replay_summary.h"
#include "rewind/replay/replay_writer.h"

namespace rwd::replay::io_test {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using TimePoint = std::chrono::steady_clock::time_point;

inline v1::ReplayHeader test_header(uint32_t players = 3) {
  v1::ReplayHeader h;
  h.set_game("crates");
  h.set_player_count(players);
  h.set_seed(42);
  h.set_tick_rate_hz(60);
  h.set_window_ticks(8);
  h.set_server_version("test");
  h.set_keyframe_interval(4);
  // The identity make_replay_header() records. This test links no engine,
  // so opaque bytes stand in for an encoded world config.
  h.set_engine("rewind-sim");
  h.set_sim_revision(2);
  h.set_rules_version(2);
  h.set_world_config(std::string(61, '\x01'));
  return h;
}

inline std::vector<rwd::PlayerInput> inputs_for(Tick tick, uint32_t players) {
  std::vector<rwd::PlayerInput> inputs(players);
  for (uint32_t p = 0; p < players; ++p) {
    inputs[p] = rwd::stick_input(static_cast<int16_t>(tick * 10 - static_cast<int>(p)),
                                 static_cast<int16_t>(-tick), static_cast<uint32_t>(tick) ^ p);
  }
  return inputs;
}

inline uint64_t checksum_for(Tick tick) {
  return 0x9E3779B97F4A7C15ull * static_cast<uint64_t>(tick + 1);
}

// A fresh path under the test temp dir, removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_((fs::path(testing::TempDir()) / (name + "_" + std::to_string(::getpid()) + ".rwr"))
                  .string()) {
    fs::remove(path_);
  }
  ~TempFile() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

inline std::vector<uint8_t> read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_all(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

inline uint64_t file_size(const std::string& path) {
  return fs::file_size(path);
}

// Writes header, ticks 0..ticks-1 with keyframes after ticks 1 and 3, and an
// end record. Returns the frame start offsets (record i starts at [i]) and the
// file end as the last element.
inline std::vector<uint64_t> write_small_replay(const std::string& path, Tick ticks = 5) {
  Result<ReplayWriter> w = ReplayWriter::open(path, test_header());
  EXPECT_TRUE(w.ok()) << w.status().message();
  for (Tick t = 0; t < ticks; ++t) {
    EXPECT_TRUE(w->append_tick(t, inputs_for(t, 3), t == 2 ? 0b101u : 0u, checksum_for(t)).ok());
    if (t == 1 || t == 3) {
      const std::vector<uint8_t> state(17, static_cast<uint8_t>(t));
      EXPECT_TRUE(w->append_keyframe(t, state).ok());
    }
  }
  EXPECT_TRUE(w->finish(ticks - 1, "match over").ok());

  // Recover frame boundaries by walking the lengths.
  const std::vector<uint8_t> bytes = read_all(path);
  std::vector<uint64_t> starts;
  uint64_t at = kMagic.size();
  while (at < bytes.size()) {
    starts.push_back(at);
    const uint32_t len = uint32_t{bytes[at]} | uint32_t{bytes[at + 1]} << 8 |
                         uint32_t{bytes[at + 2]} << 16 | uint32_t{bytes[at + 3]} << 24;
    at += kFrameHeaderBytes + len;
  }
  EXPECT_EQ(at, bytes.size());
  starts.push_back(at);
  return starts;
}

// Reads every record after the header; returns the error message or "".
inline std::string drain(ReplayReader& reader, std::vector<v1::ReplayRecord>* records = nullptr) {
  while (true) {
    Result<std::optional<v1::ReplayRecord>> r = reader.next();
    if (!r.ok()) return r.status().message();
    if (!r->has_value()) return "";
    if (records != nullptr) records->push_back(**r);
  }
}

// Builds files record by record, bypassing the writer's checks.
struct FileBuilder {
  std::vector<uint8_t> bytes{kMagic.begin(), kMagic.end()};
  FileBuilder& header(const v1::ReplayHeader& h) {
    v1::ReplayRecord r;
    *r.mutable_header() = h;
    r.mutable_header()->set_format_version(kFormatVersion);
    return add(r);
  }
  FileBuilder& tick(Tick t, uint32_t players = 3) {
    v1::ReplayRecord r;
    r.mutable_tick()->set_tick(t);
    for (const rwd::PlayerInput& in : inputs_for(t, players)) {
      *r.mutable_tick()->add_inputs() = proto::to_wire(in);
    }
    return add(r);
  }
  FileBuilder& add(const v1::ReplayRecord& r) {
    EXPECT_TRUE(append_frame(r, bytes).ok());
    return *this;
  }
  std::string open_error() const {
    Result<ReplayReader> reader = ReplayReader::from_bytes(bytes);
    return reader.ok() ? "" : reader.status().message();
  }
  std::string read_error() const {
    Result<ReplayReader> reader = ReplayReader::from_bytes(bytes);
    if (!reader.ok()) return "open: " + reader.status().message();
    return drain(*reader);
  }
};

}  // namespace rwd::replay::io_test
