// SPDX-License-Identifier: MIT
// Fuzz entry points. Each `fuzz_<name>_one` takes arbitrary bytes, must
// never crash, and aborts when a parser invariant is broken. libFuzzer
// binaries call them through a generated LLVMFuzzerTestOneInput wrapper
// (libfuzzer_main.cpp.in); fuzz_corpus_tests calls them over a deterministic
// corpus. Add one declaration per new entry file.
#pragma once
#include <cstddef>
#include <cstdint>

/// Envelope datagrams: decode_envelope, then re-encode what it accepts.
int fuzz_envelope_one(const uint8_t* data, size_t size);

/// Replay files (first byte: 1 = repair frame hashes first): ReplayReader,
/// then re-frame what it accepts and read it again.
int fuzz_replay_reader_one(const uint8_t* data, size_t size);

/// Serialized simulations (resync snapshots, desync dumps):
/// Simulation::deserialize, then round trip and step what it accepts.
int fuzz_sim_snapshot_one(const uint8_t* data, size_t size);

/// 3D world snapshots with joints: World3D::deserialize, then re-encode,
/// step and reload what it accepts.
int fuzz_world3d_snapshot_one(const uint8_t* data, size_t size);

/// Secure-connection packets and tokens: read_connect_token, from_hex, the
/// server's request and response handlers, the client's challenge handler
/// and a session's payload opener; none may accept what lacks the keys.
int fuzz_secure_packet_one(const uint8_t* data, size_t size);

/// Control API requests: the HTTP endpoints' request parser, ControlApi's
/// rules (bearer keys, quotas, ownership) against a stand-in server, and
/// parse_match_request on the bytes as a query.
int fuzz_control_request_one(const uint8_t* data, size_t size);

/// Agones GameServer records (JSON): parse_agones_game_server, the match
/// settings of what it accepts applied or refused whole, and the record
/// written back as a document read back equal.
int fuzz_agones_game_server_one(const uint8_t* data, size_t size);

/// Whole HTTP/1.1 responses: parse_http_response (the HTTP client's Beast
/// parser), then re-frame what it accepts by Content-Length and read it back
/// the same.
int fuzz_http_response_one(const uint8_t* data, size_t size);

/// Chunk sequences (resync snapshots, desync dumps): ChunkAssembler checked
/// against a model of its rules, chunk by chunk.
int fuzz_chunk_assembler_one(const uint8_t* data, size_t size);

/// View bundles (the viewer's files): decode_view_bundle, the re-encoding of
/// what it accepts, and a replay player's first steps and desync report.
int fuzz_view_bundle_one(const uint8_t* data, size_t size);

/// Live tick batches (what a spectating viewer polls): decode_live_ticks,
/// the re-encoding of what it accepts, and appending it to a player.
int fuzz_live_ticks_one(const uint8_t* data, size_t size);
