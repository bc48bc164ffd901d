#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Joins without an address cookie against a tokenless rewind-server
(tests/integration/late_join_test.sh tokenless).

  probe SERVER_PORT
         From an address that never echoed a cookie (the server cannot tell
         it from a forged one): a 4-byte join, clear-text joins for a player
         and a spectator seat, a join carrying a made-up cookie, hellos of the
         wrong size. None may be answered. Then one proper hello: exactly one
         cookie back, no larger than the hello. Exits 1 otherwise, or if the
         server sent more bytes than it received. Run it in the lobby and with
         a late-join slot open: either way no seat is taken.
"""
import json
import select
import socket
import sys
import time

HELLO_BYTES = 64
COOKIE_REPLY_BYTES = 17


def join_envelope(nonce: int, spectator: bool) -> bytes:
    # Envelope{protocol_version 3, join_request{game "crates", nonce, spectator}}
    request = b"\x0a\x06crates" + b"\x20" + bytes([nonce]) + (b"\x28\x01" if spectator else b"")
    return b"\x08\x03" + b"\x52" + bytes([len(request)]) + request


def probe(port: int) -> int:
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("127.0.0.1", 0))
    server = ("127.0.0.1", port)
    sent = received = 0
    replies = []

    def send(data: bytes):
        nonlocal sent
        sock.sendto(data, server)
        sent += len(data)

    def drain(wait: float):
        nonlocal received
        end = time.time() + wait
        while time.time() < end:
            ready, _, _ = select.select([sock], [], [], max(0.0, end - time.time()))
            if not ready:
                break
            data, _ = sock.recvfrom(2048)
            received += len(data)
            replies.append(data)

    for i in range(3):
        send(b"\x08\x03\x52\x00")
        send(join_envelope(i + 1, spectator=False))
        send(join_envelope(i + 10, spectator=True))
        send(b"\xb3" + bytes(16) + join_envelope(i + 20, spectator=False))
        send(b"\xb1\x01")
        send(b"\xb1\x01" + bytes(998))
    drain(0.5)
    if replies:
        print(f"probe: the server answered joins without a cookie: {[len(r) for r in replies]}",
              file=sys.stderr)
        return 1
    send(b"\xb1\x01" + bytes(HELLO_BYTES - 2))
    drain(0.5)
    if len(replies) != 1 or replies[0][0] != 0xB2 or len(replies[0]) != COOKIE_REPLY_BYTES:
        print(f"probe: expected one {COOKIE_REPLY_BYTES}-byte cookie, got "
              f"{[len(r) for r in replies]}", file=sys.stderr)
        return 1
    print(json.dumps({"sent_bytes": sent, "received_bytes": received,
                      "amplification": received / sent}))
    return 0 if received < sent else 1


def main() -> int:
    if len(sys.argv) == 3 and sys.argv[1] == "probe":
        return probe(int(sys.argv[2]))
    print(__doc__, file=sys.stderr)
    return 64


if __name__ == "__main__":
    sys.exit(main())
