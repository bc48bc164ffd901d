// SPDX-License-Identifier: MIT
#include "rewind/net/envelope_codec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "envelope_samples.h"

namespace rwd::net {
namespace {

using testing::header;
using testing::raw_bytes;
using testing::sample_envelopes;

// The messages have no maps, so equal fields serialize to equal bytes.
bool same(const v1::Envelope& a, const v1::Envelope& b) {
  return a.SerializeAsString() == b.SerializeAsString();
}

// What a failed comparison prints: the envelope's bytes (the lite runtime
// has no text format).
std::string hex_of(const v1::Envelope& e) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  for (const unsigned char c : e.SerializeAsString()) {
    out += kDigits[c >> 4];
    out += kDigits[c & 15];
  }
  return out;
}

// Decodes the raw serialization of `e` and expects a kCorrupt error whose
// message contains `needle`.
void expect_rejected(const v1::Envelope& e, const std::string& needle) {
  const std::vector<uint8_t> bytes = raw_bytes(e);
  Result<v1::Envelope> r = decode_envelope(bytes);
  ASSERT_FALSE(r.ok()) << "accepted, expected: " << needle;
  EXPECT_EQ(r.status().code(), ErrorCode::kCorrupt);
  EXPECT_NE(r.status().message().find(needle), std::string::npos) << r.status().message();
  // The encoder refuses what the decoder would refuse.
  std::vector<uint8_t> out = {1, 2, 3};
  EXPECT_FALSE(encode_envelope(e, out).ok());
  EXPECT_TRUE(out.empty());
}

TEST(EnvelopeCodec, RoundTripsEveryPayloadKind) {
  const std::vector<v1::Envelope> samples = sample_envelopes();
  std::set<int> kinds;
  for (const v1::Envelope& e : samples) {
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(encode_envelope(e, bytes).ok()) << hex_of(e);
    EXPECT_LE(bytes.size(), kMaxDatagramBytes);
    Result<v1::Envelope> decoded = decode_envelope(bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.status().message();
    EXPECT_TRUE(same(*decoded, e)) << hex_of(*decoded);
    kinds.insert(e.payload_case());
  }
  // Every member of the payload oneof has a sample: counted in the schema
  // itself (the lite runtime carries no descriptors).
  std::ifstream schema(REWIND_ENVELOPE_PROTO);
  ASSERT_TRUE(schema) << REWIND_ENVELOPE_PROTO;
  size_t members = 0;
  bool inside = false;
  for (std::string line; std::getline(schema, line);) {
    if (line.find("oneof payload {") != std::string::npos) {
      inside = true;
    } else if (inside && line.find('}') != std::string::npos) {
      break;
    } else if (inside && line.find(" = ") != std::string::npos) {
      ++members;
    }
  }
  EXPECT_EQ(members, 14u);
  EXPECT_EQ(kinds.size(), members);
}

TEST(EnvelopeCodec, DecodesIntoAReusedEnvelope) {
  // One message decoded into over and over (as the server does on an
  // arena) holds exactly the last datagram each time, nothing of the one
  // before.
  v1::Envelope reused;
  for (const v1::Envelope& e : sample_envelopes()) {
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(encode_envelope(e, bytes).ok());
    ASSERT_TRUE(decode_envelope(bytes, reused).ok());
    EXPECT_TRUE(same(reused, e)) << hex_of(reused);
  }
  v1::Envelope bad = header();
  bad.set_protocol_version(kProtocolVersion + 1);
  bad.mutable_ping();
  const Status refused = decode_envelope(raw_bytes(bad), reused);
  EXPECT_EQ(refused.code(), ErrorCode::kCorrupt);
  EXPECT_NE(refused.message().find("protocol_version"), std::string::npos);
  EXPECT_EQ(decode_envelope({}, reused).code(), ErrorCode::kCorrupt);
}

TEST(EnvelopeCodec, AHeaderOnlyEncodeStillRefusesABadHeaderOrSize) {
  std::vector<uint8_t> out;
  v1::Envelope version = sample_envelopes()[10];
  version.set_protocol_version(kProtocolVersion + 1);
  EXPECT_EQ(encode_envelope(version, out, EncodeCheck::kHeader).code(),
            ErrorCode::kInvalidArgument);
  v1::Envelope anonymous = sample_envelopes()[10];
  anonymous.set_connection_id(0);
  EXPECT_EQ(encode_envelope(anonymous, out, EncodeCheck::kHeader).code(),
            ErrorCode::kInvalidArgument);
  EXPECT_FALSE(encode_envelope(header(), out, EncodeCheck::kHeader).ok());  // no payload
  v1::Envelope big = header();
  big.mutable_final_ticks()->set_relayed(std::string(kMaxDatagramBytes, 'x'));
  EXPECT_EQ(encode_envelope(big, out, EncodeCheck::kHeader).code(), ErrorCode::kCapacity);
  EXPECT_TRUE(out.empty());
  // What it leaves to its caller: the payload's own limits.
  v1::Envelope negative = sample_envelopes()[10];
  negative.mutable_final_ticks()->mutable_ticks(0)->set_tick(-1);
  EXPECT_FALSE(encode_envelope(negative, out).ok());
  EXPECT_TRUE(encode_envelope(negative, out, EncodeCheck::kHeader).ok());
  // And a valid envelope encodes to the same bytes either way.
  std::vector<uint8_t> full;
  ASSERT_TRUE(encode_envelope(sample_envelopes()[10], full).ok());
  ASSERT_TRUE(encode_envelope(sample_envelopes()[10], out, EncodeCheck::kHeader).ok());
  EXPECT_EQ(out, full);
}

TEST(EnvelopeCodec, RejectsEmpty) {
  Result<v1::Envelope> r = decode_envelope({});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), ErrorCode::kCorrupt);
  EXPECT_NE(r.status().message().find("empty"), std::string::npos);
}

TEST(EnvelopeCodec, RejectsOversizeDatagram) {
  std::vector<uint8_t> bytes = raw_bytes(sample_envelopes()[6]);
  bytes.resize(kMaxDatagramBytes + 1, 0);
  Result<v1::Envelope> r = decode_envelope(bytes);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("limit 1200"), std::string::npos) << r.status().message();
}

TEST(EnvelopeCodec, AcceptsExactlyMaxSize) {
  // A valid ping padded with an unknown length-delimited field (number 100,
  // ignored by this version) to exactly 1200 bytes: the limit is inclusive.
  std::vector<uint8_t> bytes = raw_bytes(sample_envelopes()[6]);
  const size_t pad = kMaxDatagramBytes - bytes.size() - 4;  // tag (2) + length varint (2)
  bytes.insert(bytes.end(), {0xA2, 0x06, static_cast<uint8_t>(0x80 | (pad & 0x7F)),
                             static_cast<uint8_t>(pad >> 7)});
  bytes.resize(kMaxDatagramBytes, 0x55);
  Result<v1::Envelope> r = decode_envelope(bytes);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_TRUE(r->has_ping());
  bytes.push_back(0);
  EXPECT_FALSE(decode_envelope(bytes).ok());
}

TEST(EnvelopeCodec, AcceptsFullSizeChunk) {
  v1::Envelope e = sample_envelopes()[11];
  ASSERT_TRUE(e.has_desync_report());
  e.mutable_desync_report()->set_chunk(std::string(kMaxChunkBytes, 'x'));
  e.set_sequence(0xFFFF'FFFFu);
  e.set_ack(0xFFFF'FFFFu);
  e.set_ack_bits(0xFFFF'FFFFu);
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encode_envelope(e, bytes).ok());
  EXPECT_LE(bytes.size(), kMaxDatagramBytes);
  EXPECT_TRUE(decode_envelope(bytes).ok());
}

TEST(EnvelopeCodec, EncodeRefusesOversize) {
  // Valid field by field, but 128 inputs at maximum varint size exceed 1200.
  v1::Envelope e = header();
  auto* m = e.mutable_input_frame();
  m->set_first_tick(0);
  m->set_last_final_tick_seen(-1);
  for (int i = 0; i < 128; ++i) m->add_inputs()->set_data(std::string(16, '\x7f'));
  std::vector<uint8_t> out = {9};
  Status s = encode_envelope(e, out);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), ErrorCode::kCapacity);
  EXPECT_TRUE(out.empty());
  // The same bytes arriving from a peer are refused too.
  EXPECT_FALSE(decode_envelope(raw_bytes(e)).ok());
}

TEST(EnvelopeCodec, RejectsUnparsableProtobuf) {
  // Field 3 (sequence, varint) with a truncated varint.
  const std::vector<uint8_t> truncated_varint = {0x18, 0xFF, 0xFF};
  // Field 10 (join_request) length-delimited, claiming 50 bytes but holding 1.
  const std::vector<uint8_t> short_length = {0x52, 50, 0x00};
  // Wire type 7 does not exist.
  const std::vector<uint8_t> bad_wire_type = {0x0F, 0x00};
  for (const auto& bytes : {truncated_varint, short_length, bad_wire_type}) {
    Result<v1::Envelope> r = decode_envelope(bytes);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("not a valid protobuf"), std::string::npos)
        << r.status().message();
  }
}

TEST(EnvelopeCodec, RejectsInvalidUtf8Silently) {
  v1::Envelope e = sample_envelopes()[0];
  std::vector<uint8_t> bytes = raw_bytes(e);
  // Corrupt the first byte of "crates" (the game string) into a lone
  // continuation byte.
  const std::string game = e.join_request().game();
  auto it = std::search(bytes.begin(), bytes.end(), game.begin(), game.end());
  ASSERT_NE(it, bytes.end());
  *it = 0x80;
  ::testing::internal::CaptureStderr();
  Result<v1::Envelope> r = decode_envelope(bytes);
  const std::string logged = ::testing::internal::GetCapturedStderr();
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("not a valid protobuf"), std::string::npos);
  // A peer must not be able to write to the server's log.
  EXPECT_EQ(logged, "");
}

TEST(EnvelopeCodec, RejectsWrongProtocolVersion) {
  for (uint32_t version :
       {0u, 1u, 2u, 4u, 0xFFFF'FFFFu}) {  // 1: before address cookies, 2: stick inputs
    v1::Envelope e = sample_envelopes()[6];
    e.set_protocol_version(version);
    expect_rejected(e, "protocol_version");
  }
}

TEST(EnvelopeCodec, RejectsMissingPayload) {
  expect_rejected(header(), "no payload");
}

TEST(EnvelopeCodec, RejectsUnknownPayloadNumber) {
  // A payload field number this version does not know parses as an unknown
  // field, so the envelope has no payload.
  std::vector<uint8_t> bytes = raw_bytes(header());
  bytes.insert(bytes.end(), {0xD2, 0x02, 0x00});  // field 42, length 0
  Result<v1::Envelope> r = decode_envelope(bytes);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("no payload"), std::string::npos);
}

TEST(EnvelopeCodec, RejectsZeroConnectionIdAfterHandshake) {
  v1::Envelope e = sample_envelopes()[6];  // ping
  e.set_connection_id(0);
  expect_rejected(e, "connection_id is 0");
}

TEST(EnvelopeCodec, RejectsTooManyInputs) {
  v1::Envelope e = header();
  auto* m = e.mutable_input_frame();
  for (int i = 0; i < 129; ++i) m->add_inputs();  // zero inputs encode to 2 bytes each
  expect_rejected(e, "129 inputs, limit 128");

  v1::Envelope relayed = header();
  for (int i = 0; i < 129; ++i) relayed.mutable_relayed_inputs()->add_inputs();
  expect_rejected(relayed, "relayed_inputs has 129 inputs");
}

TEST(EnvelopeCodec, RejectsInputsBeyondTheCapacityAndStickFields) {
  v1::Envelope e = sample_envelopes()[8];
  e.mutable_input_frame()->mutable_inputs(3)->set_data(std::string(rwd::kInputCapacity + 1, 'x'));
  expect_rejected(e, "input_frame.inputs[3] has 33 bytes, limit 32");
  // One form per input: trailing zeros are left out.
  v1::Envelope zero = sample_envelopes()[8];
  zero.mutable_input_frame()->mutable_inputs(3)->set_data(std::string("\x01\x00", 2));
  expect_rejected(zero, "input_frame.inputs[3] ends in a zero byte");
  // Protocol 3 carries the game's bytes; the stick fields are for old replays.
  v1::Envelope f = sample_envelopes()[10];
  f.mutable_final_ticks()->mutable_ticks(1)->mutable_inputs(2)->set_axis_y(5);
  expect_rejected(f, "final_ticks.ticks[1].inputs[2] sets the stick fields");
}

TEST(EnvelopeCodec, AcceptsAFullInput) {
  v1::Envelope e = sample_envelopes()[8];
  e.mutable_input_frame()->mutable_inputs(0)->set_data(std::string(rwd::kInputCapacity, '\xff'));
  EXPECT_TRUE(decode_envelope(raw_bytes(e)).ok());
}

TEST(EnvelopeCodec, RejectsBadInputRuns) {
  v1::Envelope player = sample_envelopes()[8];
  player.mutable_input_frame()->set_player(64);
  expect_rejected(player, "input_frame.player 64");

  v1::Envelope negative = sample_envelopes()[8];
  negative.mutable_input_frame()->set_first_tick(-5);
  expect_rejected(negative, "first_tick -5");

  // The last tick would overflow int32.
  v1::Envelope overflow = sample_envelopes()[8];
  overflow.mutable_input_frame()->set_first_tick(2147483647 - 3);
  expect_rejected(overflow, "first_tick");

  v1::Envelope seen = sample_envelopes()[8];
  seen.mutable_input_frame()->set_last_final_tick_seen(-2);
  expect_rejected(seen, "last_final_tick_seen");
}

TEST(EnvelopeCodec, RejectsTooManyFinalTicks) {
  v1::Envelope e = header();
  for (int t = 0; t < 65; ++t) e.mutable_final_ticks()->add_ticks()->set_tick(t);
  expect_rejected(e, "final_ticks has 65 ticks, limit 64");

  v1::Envelope players = header();
  auto* ft = players.mutable_final_ticks()->add_ticks();
  for (int p = 0; p < 65; ++p) ft->add_inputs();
  expect_rejected(players, "65 inputs, limit 64");

  v1::Envelope negative = sample_envelopes()[10];
  negative.mutable_final_ticks()->mutable_ticks(0)->set_tick(-1);
  expect_rejected(negative, "ticks[0].tick -1");
}

TEST(EnvelopeCodec, RejectsLongStrings) {
  const std::string long_string(257, 'a');
  v1::Envelope game = sample_envelopes()[0];
  game.mutable_join_request()->set_game(long_string);
  expect_rejected(game, "join_request.game is 257 bytes, limit 256");

  v1::Envelope name = sample_envelopes()[0];
  name.mutable_join_request()->set_client_name(std::string(65, 'n'));
  expect_rejected(name, "client_name is 65 bytes, limit 64");

  v1::Envelope reject = sample_envelopes()[2];
  reject.mutable_join_reject()->set_reason(long_string);
  expect_rejected(reject, "join_reject.reason");

  v1::Envelope end = sample_envelopes()[4];
  end.mutable_match_end()->set_reason(long_string);
  expect_rejected(end, "match_end.reason");

  v1::Envelope bye = sample_envelopes()[5];
  bye.mutable_disconnect()->set_reason(long_string);
  expect_rejected(bye, "disconnect.reason");

  v1::Envelope accept = sample_envelopes()[1];
  accept.mutable_join_accept()->set_game(long_string);
  expect_rejected(accept, "join_accept.game");

  // 256 bytes is still fine.
  v1::Envelope ok = sample_envelopes()[5];
  ok.mutable_disconnect()->set_reason(std::string(256, 'b'));
  EXPECT_TRUE(decode_envelope(raw_bytes(ok)).ok());
}

TEST(EnvelopeCodec, RejectsBadJoinAccept) {
  const std::vector<std::pair<std::function<void(v1::JoinAccept*)>, std::string>> cases = {
      {[](v1::JoinAccept* m) { m->set_connection_id(0); }, "join_accept.connection_id is 0"},
      {[](v1::JoinAccept* m) { m->set_player_count(0); }, "player_count 0"},
      {[](v1::JoinAccept* m) { m->set_player_count(65); }, "player_count 65"},
      {[](v1::JoinAccept* m) { m->set_player(4); }, "player 4 >= player_count 4"},
      {[](v1::JoinAccept* m) { m->set_tick_rate_hz(0); }, "tick_rate_hz 0"},
      {[](v1::JoinAccept* m) { m->set_tick_rate_hz(1001); }, "tick_rate_hz 1001"},
  };
  for (const auto& [mutate, needle] : cases) {
    v1::Envelope e = sample_envelopes()[1];
    mutate(e.mutable_join_accept());
    expect_rejected(e, needle);
  }
}

TEST(EnvelopeCodec, RejectsBadChunks) {
  using Mutation = std::function<void(v1::Envelope&)>;
  const std::vector<std::pair<Mutation, std::string>> cases = {
      {[](v1::Envelope& e) { e.mutable_resync_chunk()->set_chunk(std::string(1101, 'c')); },
       "resync_chunk.chunk is 1101 bytes, limit 1100"},
      {[](v1::Envelope& e) { e.mutable_resync_chunk()->set_chunk_index(2); },
       "resync_chunk.chunk_index 2 >= chunk_count 2"},
      {[](v1::Envelope& e) { e.mutable_resync_chunk()->set_chunk_count(0); },
       "resync_chunk.chunk_count 0"},
      {[](v1::Envelope& e) { e.mutable_resync_chunk()->set_chunk_count(1025); },
       "resync_chunk.chunk_count 1025"},
      {[](v1::Envelope& e) { e.mutable_resync_chunk()->set_total_size(3000); },
       "resync_chunk.total_size 3000"},
      {[](v1::Envelope& e) { e.mutable_resync_chunk()->set_total_size(10); },
       "chunk larger than total_size"},
      {[](v1::Envelope& e) { e.mutable_resync_chunk()->set_tick(-1); }, "resync_chunk.tick"},
  };
  for (const auto& [mutate, needle] : cases) {
    v1::Envelope e = sample_envelopes()[12];
    ASSERT_TRUE(e.has_resync_chunk());
    mutate(e);
    expect_rejected(e, needle);
  }
  v1::Envelope desync = sample_envelopes()[11];
  ASSERT_TRUE(desync.has_desync_report());
  desync.mutable_desync_report()->set_chunk_count(257);
  expect_rejected(desync, "desync_report.chunk_count 257 not in [1, 256]");
  v1::Envelope big = sample_envelopes()[11];
  big.mutable_desync_report()->set_chunk_count(256);
  big.mutable_desync_report()->set_total_size((1u << 20) + 1);
  expect_rejected(big, "desync_report.total_size");
  v1::Envelope resync_request = sample_envelopes()[13];
  resync_request.mutable_resync_request()->set_desync_tick(-1);
  expect_rejected(resync_request, "resync_request.desync_tick");
  v1::Envelope refused = sample_envelopes()[13];
  refused.mutable_resync_request()->set_refused_snapshot_id(4);
  refused.mutable_resync_request()->set_refused_reason(std::string(257, 'x'));
  expect_rejected(refused, "resync_request.refused_reason");
}

TEST(EnvelopeCodec, RandomBytesNeverCrash) {
  // xorshift so the corpus is the same on every run.
  uint64_t x = 0x243F'6A88'85A3'08D3ull;
  auto next = [&x] {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  int decoded = 0;
  std::vector<uint8_t> bytes;
  for (int i = 0; i < 10'000; ++i) {
    bytes.resize(next() % (kMaxDatagramBytes + 64));
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(next());
    Result<v1::Envelope> r = decode_envelope(bytes);
    if (r.ok()) {
      ++decoded;
      // Anything accepted must survive validation and re-encode.
      std::vector<uint8_t> again;
      EXPECT_TRUE(encode_envelope(*r, again).ok()) << hex_of(*r);
    } else {
      EXPECT_EQ(r.status().code(), ErrorCode::kCorrupt);
      EXPECT_FALSE(r.status().message().empty());
    }
  }
  // Random bytes essentially never carry version 1 plus a valid payload.
  EXPECT_LT(decoded, 100);
}

TEST(EnvelopeCodec, TruncationsAndBitFlipsNeverCrash) {
  uint64_t x = 0x1357'9BDF'2468'ACE0ull;
  auto next = [&x] {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  int accepted = 0;
  int rejected = 0;
  for (const v1::Envelope& e : sample_envelopes()) {
    std::vector<uint8_t> valid;
    ASSERT_TRUE(encode_envelope(e, valid).ok());
    for (size_t cut = 0; cut < valid.size(); ++cut) {
      Result<v1::Envelope> r = decode_envelope(std::span(valid).first(cut));
      r.ok() ? ++accepted : ++rejected;
    }
    for (int i = 0; i < 1000; ++i) {
      std::vector<uint8_t> flipped = valid;
      const int flips = 1 + static_cast<int>(next() % 4);
      for (int f = 0; f < flips; ++f) {
        flipped[next() % flipped.size()] ^= static_cast<uint8_t>(1u << (next() % 8));
      }
      Result<v1::Envelope> r = decode_envelope(flipped);
      if (r.ok()) {
        ++accepted;
        std::vector<uint8_t> again;
        EXPECT_TRUE(encode_envelope(*r, again).ok());
      } else {
        ++rejected;
      }
    }
  }
  // Both outcomes occur: flips in payload values often stay valid, flips in
  // tags and lengths do not.
  EXPECT_GT(accepted, 0);
  EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace rwd::net
