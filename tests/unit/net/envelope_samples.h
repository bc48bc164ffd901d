// SPDX-License-Identifier: MIT
// One valid envelope per payload kind, shared by the unit tests and the fuzz
// corpus generator.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rewind/core/stick_input.h"
#include "rewind/net/envelope_codec.h"
#include "rewind/proto/input_packing.h"
#include "rewind/proto/message_inputs.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::net::testing {

inline v1::Envelope header(uint64_t connection_id = 0x1234'5678'9ABC'DEF0ull) {
  v1::Envelope e;
  e.set_protocol_version(kProtocolVersion);
  e.set_connection_id(connection_id);
  e.set_sequence(77);
  e.set_ack(41);
  e.set_ack_bits(0xF0F0'0001u);
  return e;
}

inline void fill_input(v1::Input* input, int i) {
  // Up to eight bytes, the last one never zero (trailing zeros are left out).
  std::string data;
  for (int b = 0; b <= i % 8; ++b) data.push_back(static_cast<char>(1 + (i * 37 + b * 53) % 255));
  input->set_data(data);
}

/// Every payload kind, each valid and within kMaxDatagramBytes.
inline std::vector<v1::Envelope> sample_envelopes() {
  std::vector<v1::Envelope> out;
  {
    v1::Envelope e = header(0);
    auto* m = e.mutable_join_request();
    m->set_game("crates");
    m->set_client_name("bot-17");
    m->set_nonce(0xDEAD'BEEF'CAFE'F00Dull);
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    auto* m = e.mutable_join_accept();
    m->set_nonce(9);
    m->set_connection_id(0x1234'5678'9ABC'DEF0ull);
    m->set_player(3);
    m->set_player_count(4);
    m->set_game("crates");
    m->set_seed(42);
    m->set_tick_rate_hz(60);
    m->set_window_ticks(8);
    out.push_back(e);
  }
  {
    v1::Envelope e = header(0);
    e.mutable_join_reject()->set_nonce(9);
    e.mutable_join_reject()->set_reason("match full");
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    e.mutable_match_start()->set_start_tick(0);
    e.mutable_match_start()->set_server_tick(-3);
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    e.mutable_match_end()->set_last_final_tick(3600);
    e.mutable_match_end()->set_reason("time limit");
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    e.mutable_disconnect()->set_reason("bye");
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    e.mutable_ping()->set_client_time_us(123'456'789);
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    e.mutable_pong()->set_client_time_us(123'456'789);
    e.mutable_pong()->set_server_tick(500);
    e.mutable_pong()->set_server_tick_elapsed_us(8'000);
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    auto* m = e.mutable_input_frame();
    m->set_player(1);
    m->set_first_tick(1000);
    m->set_last_final_tick_seen(990);
    for (int i = 0; i < 20; ++i) fill_input(m->add_inputs(), i);
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    auto* m = e.mutable_relayed_inputs();
    m->set_player(2);
    m->set_first_tick(7);
    for (int i = 0; i < 5; ++i) fill_input(m->add_inputs(), i);
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    auto* m = e.mutable_final_ticks();
    for (int t = 0; t < 4; ++t) {
      auto* ft = m->add_ticks();
      ft->set_tick(200 + t);
      for (int p = 0; p < 4; ++p) fill_input(ft->add_inputs(), t * 4 + p);
      ft->set_substituted_mask(t == 2 ? 0b0100u : 0u);
      ft->set_checksum(0x0123'4567'89AB'CDEFull + static_cast<uint64_t>(t));
    }
    m->set_input_ack_tick(205);
    m->set_input_lead_ticks(-2);
    m->set_server_tick(210);
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    auto* m = e.mutable_desync_report();
    m->set_tick(321);
    m->set_client_checksum(1);
    m->set_server_checksum(2);
    m->set_report_id(5);
    m->set_chunk_index(1);
    m->set_chunk_count(3);
    m->set_total_size(3000);
    m->set_chunk(std::string(1000, 'd'));
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    auto* m = e.mutable_resync_chunk();
    m->set_snapshot_id(8);
    m->set_tick(322);
    m->set_checksum(3);
    m->set_chunk_index(0);
    m->set_chunk_count(2);
    m->set_total_size(1500);
    m->set_chunk(std::string(kMaxChunkBytes, 'r'));
    out.push_back(e);
  }
  {
    v1::Envelope e = header();
    e.mutable_resync_request()->set_desync_tick(321);
    out.push_back(e);
  }
  {
    // Final ticks with packed inputs (the first standalone, the others
    // against the tick before) and packed relayed runs, as servers send
    // them.
    v1::Envelope e = header();
    auto* m = e.mutable_final_ticks();
    std::vector<rwd::PlayerInput> previous;
    for (int t = 0; t < 3; ++t) {
      std::vector<rwd::PlayerInput> inputs;
      for (int p = 0; p < 4; ++p) {
        inputs.push_back(rwd::stick_input(static_cast<int16_t>(p * 250 - 500),
                                          static_cast<int16_t>(t == 2 ? 707 : 0),
                                          static_cast<uint32_t>(p == 1 ? 3 : 0)));
      }
      auto* ft = m->add_ticks();
      ft->set_tick(300 + t);
      ft->set_checksum(0xFEDCull + static_cast<uint64_t>(t));
      if (t == 0) {
        proto::pack_inputs(inputs, {}, *ft->mutable_packed_inputs());
      } else {
        proto::pack_inputs(inputs, previous, *ft->mutable_packed_inputs());
        ft->set_delta(true);
      }
      previous = inputs;
    }
    const std::vector<rwd::PlayerInput> run_inputs = {
        rwd::stick_input(1000, -1000, 1), rwd::stick_input(1000, -1000, 1), rwd::PlayerInput{}};
    proto::append_relayed_run(3, 304, 306, run_inputs, *m->mutable_relayed());
    proto::append_relayed_run(1, 309, 306, run_inputs, *m->mutable_relayed());
    m->set_input_ack_tick(305);
    m->set_server_tick(306);
    out.push_back(e);
  }
  return out;
}

/// Serializes without any validation, to build datagrams the codec must refuse.
inline std::vector<uint8_t> raw_bytes(const v1::Envelope& e) {
  std::vector<uint8_t> bytes(e.ByteSizeLong());
  if (!bytes.empty()) (void)e.SerializeToArray(bytes.data(), static_cast<int>(bytes.size()));
  return bytes;
}

}  // namespace rwd::net::testing
