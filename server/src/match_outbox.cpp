// SPDX-License-Identifier: MIT
#include "rewind/server/match_outbox.h"

#include "host_log.h"
#include "rewind/net/envelope_codec.h"

namespace rwd::server {

void MatchOutbox::send(Seat& seat, v1::Envelope& envelope, TimePoint now) {
  if (!seat.connection) return;
  seat.connection->stamp(envelope, now);
  // Checking packed final ticks again would unpack every packed input for
  // every client.
  const net::EncodeCheck check =
      envelope.has_final_ticks() ? net::EncodeCheck::kHeader : net::EncodeCheck::kFull;
  if (Status status = net::encode_envelope(envelope, encode_buffer_, check); !status.ok()) {
    detail::log_line("dropping an unencodable message: " + status.message());
    return;
  }
  ++stats_.packets_out;
  stats_.bytes_out += encode_buffer_.size();
  send_(seat.endpoint, encode_buffer_);
}

void MatchOutbox::send_unconnected(const Endpoint& to, v1::Envelope& envelope) {
  envelope.set_protocol_version(net::kProtocolVersion);
  if (Status status = net::encode_envelope(envelope, encode_buffer_); !status.ok()) return;
  ++stats_.packets_out;
  stats_.bytes_out += encode_buffer_.size();
  send_(to, encode_buffer_);
}

}  // namespace rwd::server
