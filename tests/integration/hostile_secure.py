#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Hostile clients against a secure rewind-server (tests/integration/secure_match_test.sh).

  probe  SERVER_PORT TOKENS FOREIGN_TOKEN
         Before the players come: clear-text join requests (lobby takeover),
         a request built from a token of another server key, the stolen sealed
         part of a real token replayed from this address (it gets a challenge
         it cannot read), and forged responses. Exits 1 if the server answers
         anything but that challenge, or answers more bytes than it received.
  copied SERVER_PORT TOKENS
         While the match runs: every player's token, copied (keys included),
         presented from new addresses. A token connects once, so none gets a
         challenge. Exits 1 if the server answers any.
  proxy  LISTEN_PORT_FILE SERVER_PORT SECONDS
         A UDP relay between the bots and the server that also attacks: every
         client datagram is replayed (from its own address and from another),
         some are altered, and some get their sequence raised by a million.
         Prints the counts as JSON when it ends.
"""
import json
import os
import random
import select
import socket
import sys
import time

REQUEST_BYTES = 1000


def request_from_token(token: bytes) -> bytes:
    # token: version | match tag 8 | expiry 8 | slot 4 | client id 8 | keys 64 | nonce 24 | sealed
    version, match_tag, expiry, slot = token[0:1], token[1:9], token[9:17], token[17:21]
    nonce_and_sealed = token[21 + 8 + 64:]
    packet = b"\xc1" + version + match_tag + expiry + slot + nonce_and_sealed
    return packet + bytes(REQUEST_BYTES - len(packet))


def probe(port: int, tokens_path: str, foreign_path: str) -> int:
    tokens = [bytes.fromhex(line) for line in open(tokens_path).read().split()]
    foreign = bytes.fromhex(open(foreign_path).read().strip())
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

    # Clear-text JoinRequests (an Envelope with a join_request payload), as a
    # tokenless server would take them.
    for i in range(4):
        send(bytes([0x08, 0x01, 0x52, 0x0A, 0x0A, 0x06]) + b"crates" + bytes([0x20, i + 1]))
    drain(0.3)
    if replies:
        print("probe: the server answered a clear-text join", file=sys.stderr)
        return 1
    send(request_from_token(foreign))
    send(request_from_token(tokens[0])[:-1])  # wrong size
    drain(0.3)
    if replies:
        print("probe: the server answered a foreign or malformed request", file=sys.stderr)
        return 1
    # The stolen sealed part of a real token: a challenge comes back, sealed
    # with a key this client does not have.
    send(request_from_token(tokens[0]))
    drain(0.5)
    if len(replies) != 1 or replies[0][0] != 0xC2 or len(replies[0]) >= REQUEST_BYTES:
        print(f"probe: expected one challenge smaller than the request, got "
              f"{[len(r) for r in replies]}", file=sys.stderr)
        return 1
    challenge = replies[0]
    replies.clear()
    # Forged responses: the right size, random contents or the challenge's
    # own bytes moved around.
    for _ in range(8):
        send(b"\xc3" + os.urandom(len(challenge) - 1 - 24))
    send(b"\xc3" + challenge[25:])
    send(b"\xc4" + os.urandom(60))
    drain(0.5)
    if replies:
        print("probe: the server answered a forged response or payload", file=sys.stderr)
        return 1
    print(json.dumps({"sent_bytes": sent, "received_bytes": received,
                      "amplification": received / sent}))
    return 0 if received < sent else 1


def copied(port: int, tokens_path: str) -> int:
    tokens = [bytes.fromhex(line) for line in open(tokens_path).read().split()]
    server = ("127.0.0.1", port)
    socks = []
    for token in tokens:
        sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        sock.bind(("127.0.0.1", 0))
        socks.append(sock)
        for _ in range(3):  # resent, as a client would until answered
            sock.sendto(request_from_token(token), server)
    replies = 0
    end = time.time() + 0.5
    while time.time() < end:
        ready, _, _ = select.select(socks, [], [], max(0.0, end - time.time()))
        for s in ready:
            s.recvfrom(2048)
            replies += 1
    print(json.dumps({"copied_tokens": len(tokens), "replies": replies}))
    return 0 if replies == 0 else 1


def proxy(port_file: str, server_port: int, seconds: float) -> int:
    listen = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    listen.bind(("127.0.0.1", 0))
    attacker = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    attacker.bind(("127.0.0.1", 0))
    with open(port_file + ".tmp", "w") as f:
        f.write(str(listen.getsockname()[1]))
    os.replace(port_file + ".tmp", port_file)
    server = ("127.0.0.1", server_port)
    upstream = {}  # client address -> socket toward the server
    client_of = {}  # upstream socket -> client address
    rng = random.Random(7)
    counts = {"relayed": 0, "replayed": 0, "replayed_other_address": 0, "altered": 0,
              "sequence_jumps": 0}
    held = []
    end = time.time() + seconds
    while time.time() < end:
        ready, _, _ = select.select([listen, attacker] + list(client_of), [], [], 0.05)
        for s in ready:
            data, source = s.recvfrom(2048)
            if s is listen:
                if source not in upstream:
                    up = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                    up.bind(("127.0.0.1", 0))
                    upstream[source] = up
                    client_of[up] = source
                up = upstream[source]
                up.sendto(data, server)
                counts["relayed"] += 1
                if data[:1] == b"\xc4":
                    held.append((up, data))
                    attacker.sendto(data, server)
                    counts["replayed_other_address"] += 1
                    if rng.random() < 0.2:
                        bad = bytearray(data)
                        bad[rng.randrange(9, len(bad))] ^= 1 << rng.randrange(8)
                        up.sendto(bytes(bad), server)
                        counts["altered"] += 1
                    if rng.random() < 0.1:
                        jump = bytearray(data)
                        seq = int.from_bytes(jump[1:9], "little") + 1_000_000
                        jump[1:9] = seq.to_bytes(8, "little")
                        up.sendto(bytes(jump), server)
                        counts["sequence_jumps"] += 1
            elif s is attacker:
                pass  # whatever the server says to a stranger (it should say nothing)
            else:
                listen.sendto(data, client_of[s])
        # Replay what the clients sent a little earlier, from their own address.
        while len(held) > 30:
            up, data = held.pop(0)
            up.sendto(data, server)
            counts["replayed"] += 1
    print(json.dumps(counts))
    return 0


def main() -> int:
    if len(sys.argv) == 5 and sys.argv[1] == "probe":
        return probe(int(sys.argv[2]), sys.argv[3], sys.argv[4])
    if len(sys.argv) == 4 and sys.argv[1] == "copied":
        return copied(int(sys.argv[2]), sys.argv[3])
    if len(sys.argv) == 5 and sys.argv[1] == "proxy":
        return proxy(sys.argv[2], int(sys.argv[3]), float(sys.argv[4]))
    print(__doc__, file=sys.stderr)
    return 64


if __name__ == "__main__":
    sys.exit(main())
