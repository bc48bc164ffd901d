// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rewind/core/status.h"
#include "rewind/v1/envelope.pb.h"

namespace rwd::net {

/// Wire protocol version carried in every Envelope; a receiver drops any other.
/// 2: a tokenless join travels in a cookie packet (net/address_cookie.h).
/// 3: inputs are the game's bytes (Input.data), packed with a varint mask.
inline constexpr uint32_t kProtocolVersion = 3;
/// Largest datagram Rewind sends or accepts, in bytes. Chosen to stay below
/// the common 1280-byte IPv6 minimum MTU minus IP/UDP headers, so datagrams
/// are never fragmented.
inline constexpr size_t kMaxDatagramBytes = 1200;

/// Per-message sanity limits enforced by decode_envelope and encode_envelope.
inline constexpr size_t kMaxInputsPerFrame = 128;           ///< InputFrame / RelayedInputs inputs
inline constexpr size_t kMaxFinalTicksPerPacket = 64;       ///< FinalTicks.ticks
inline constexpr uint32_t kMaxPlayerSlots = 64;             ///< substituted_mask has 64 bits
inline constexpr size_t kMaxStringBytes = 256;              ///< any string field
inline constexpr size_t kMaxClientNameBytes = 64;           ///< JoinRequest.client_name
inline constexpr size_t kMaxChunkBytes = 1100;              ///< DesyncReport / ResyncChunk chunk
inline constexpr uint32_t kMaxDesyncChunks = 256;           ///< DesyncReport.chunk_count
inline constexpr uint32_t kMaxResyncChunks = 1024;          ///< ResyncChunk.chunk_count
inline constexpr uint32_t kMaxDesyncDumpBytes = 1u << 20;   ///< DesyncReport.total_size
inline constexpr uint32_t kMaxResyncStateBytes = 4u << 20;  ///< ResyncChunk.total_size
inline constexpr uint32_t kMaxTickRateHz = 1000;            ///< JoinAccept.tick_rate_hz, >= 1

/// Parses one datagram. Never throws and never crashes, whatever the bytes.
/// Errors (all ErrorCode::kCorrupt, with a message naming the field): empty,
/// larger than kMaxDatagramBytes, not a protobuf Envelope, protocol_version
/// != kProtocolVersion, no payload, connection_id 0 on a payload other than
/// JoinRequest/JoinReject, or a payload that breaks validate_envelope().
Result<rwd::v1::Envelope> decode_envelope(std::span<const uint8_t> bytes);
/// The same into `out` (replacing its contents), so a receiver can reuse a
/// message, or one on a protobuf arena, instead of allocating one per
/// datagram. On an error `out` holds whatever was parsed: drop it.
Status decode_envelope(std::span<const uint8_t> bytes, rwd::v1::Envelope& out);

/// Checks the header and per-payload sanity limits listed above (sizes,
/// counts, axis ranges, chunk indices, non-negative ticks). Returns kCorrupt
/// with a message on the first violation. Does not check the encoded size.
Status validate_envelope(const rwd::v1::Envelope& envelope);

/// What encode_envelope checks before it serializes.
enum class EncodeCheck : uint8_t {
  /// Everything decode_envelope checks.
  kFull,
  /// The header (version, payload, connection id) and the size only: for a
  /// sender whose payload is made only of values it checked itself, where
  /// checking again would unpack every packed input it just packed (the
  /// server's per-tick FinalTicks to every client).
  kHeader,
};

/// Serializes `envelope` into `out` (replacing its contents). Refuses, leaving
/// `out` empty, anything decode_envelope would reject: an invalid envelope
/// (kInvalidArgument; with EncodeCheck::kHeader only an invalid header) or
/// one larger than kMaxDatagramBytes (kCapacity).
Status encode_envelope(const rwd::v1::Envelope& envelope, std::vector<uint8_t>& out,
                       EncodeCheck check = EncodeCheck::kFull);

}  // namespace rwd::net
