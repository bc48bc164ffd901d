// SPDX-License-Identifier: MIT
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>


#include "fuzz_entries.h"
#include "rewind/net/envelope_codec.h"

namespace {

[[noreturn]] void invariant_broken(const char* what) {
  std::fprintf(stderr, "fuzz_envelope: invariant broken: %s\n", what);
  std::abort();
}

}  // namespace

int fuzz_envelope_one(const uint8_t* data, size_t size) {
  using rwd::net::decode_envelope;
  using rwd::net::encode_envelope;
  const std::span<const uint8_t> bytes(data, size);
  rwd::Result<rwd::v1::Envelope> decoded = decode_envelope(bytes);
  if (!decoded.ok()) {
    if (decoded.status().code() != rwd::ErrorCode::kCorrupt) invariant_broken("error not kCorrupt");
    if (decoded.status().message().empty()) invariant_broken("error without message");
    return 0;
  }
  // Whatever the decoder accepts, the encoder must accept too, and the
  // result must decode to the same message (no lossy or asymmetric checks).
  std::vector<uint8_t> again;
  if (!encode_envelope(*decoded, again).ok()) invariant_broken("accepted envelope fails encode");
  rwd::Result<rwd::v1::Envelope> round = decode_envelope(again);
  if (!round.ok()) invariant_broken("re-encoded envelope fails decode");
  // No maps in the messages: equal fields serialize to equal bytes.
  if (decoded->SerializeAsString() != round->SerializeAsString()) {
    invariant_broken("round trip changed the envelope");
  }
  return 0;
}
