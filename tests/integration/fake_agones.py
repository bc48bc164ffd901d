#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A stand-in for the Agones SDK sidecar's REST API, for rewind-server --agones.

  fake_agones.py --port-file FILE --log FILE [--allocate-after S]
                 [--annotation KEY=VALUE]... [--label KEY=VALUE]...

Listens on 127.0.0.1 (a free port, written to --port-file once listening)
and answers what the real sidecar does: POST /ready, /health, /shutdown
with {}, GET /gameserver with the GameServer record. The state starts as
"Scheduled", turns "Ready" on POST /ready, "Allocated" --allocate-after
seconds later (with the given annotations and labels added, as an
allocation's metadata would), and "Shutdown" on POST /shutdown. Every call
is appended to --log as one JSON line {"t", "method", "path", "body",
"state"} (t: seconds since start), and the moment of the allocation as
{"t", "event": "allocated"}. Other paths answer 404.
"""
import argparse
import json
import os
import threading
import time
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

START = time.monotonic()


def now():
    return round(time.monotonic() - START, 3)


class Sidecar:
    def __init__(self, log_path, allocate_after, annotations, labels):
        self.lock = threading.Lock()
        self.log = open(log_path, "a", buffering=1, encoding="utf-8")
        self.allocate_after = allocate_after
        self.allocation = (annotations, labels)
        self.state = "Scheduled"
        self.ready_at = None
        self.annotations = {"agones.dev/ready-container-id": "docker://fake"}
        self.labels = {"agones.dev/fleet": "rewind"}

    def record(self, entry):
        entry["t"] = now()
        self.log.write(json.dumps(entry) + "\n")

    def advance(self):
        """Allocates once the delay since Ready has passed (under the lock)."""
        if self.state == "Ready" and now() - self.ready_at >= self.allocate_after:
            self.state = "Allocated"
            self.annotations.update(self.allocation[0])
            self.labels.update(self.allocation[1])
            self.record({"event": "allocated"})

    def game_server(self):
        return {
            "object_meta": {
                "name": "rewind-fleet-x7k2p-abcde",
                "namespace": "default",
                "uid": "0f3c2b1a-0000-4000-8000-000000000001",
                "resource_version": "4242",
                "generation": "3",
                "creation_timestamp": "1714564800",
                "annotations": dict(self.annotations),
                "labels": dict(self.labels),
            },
            "status": {
                "state": self.state,
                "address": "203.0.113.7",
                "ports": [{"name": "default", "port": 7193}],
            },
        }


class Handler(BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"
    sidecar = None  # set in main

    def log_message(self, *args):
        pass

    def answer(self, status, body):
        data = json.dumps(body).encode()
        self.send_response(status)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(data)))
        self.end_headers()
        self.wfile.write(data)

    def handle_call(self):
        length = int(self.headers.get("Content-Length") or 0)
        body = self.rfile.read(length).decode("utf-8", "replace") if length else ""
        s = self.sidecar
        with s.lock:
            s.advance()
            s.record({"method": self.command, "path": self.path, "body": body, "state": s.state})
            if self.command == "GET" and self.path == "/gameserver":
                return self.answer(200, s.game_server())
            if self.command == "POST" and self.path in ("/ready", "/health", "/shutdown"):
                if self.path == "/ready" and s.state == "Scheduled":
                    s.state = "Ready"
                    s.ready_at = now()
                elif self.path == "/shutdown":
                    s.state = "Shutdown"
                return self.answer(200, {})
            return self.answer(404, {"error": "Not Found", "code": 5})

    do_GET = handle_call
    do_POST = handle_call


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--port-file", required=True)
    parser.add_argument("--log", required=True)
    parser.add_argument("--allocate-after", type=float, default=2.0)
    parser.add_argument("--annotation", action="append", default=[])
    parser.add_argument("--label", action="append", default=[])
    args = parser.parse_args()

    def pairs(items):
        return dict(item.split("=", 1) for item in items)

    Handler.sidecar = Sidecar(args.log, args.allocate_after, pairs(args.annotation),
                              pairs(args.label))
    server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    temporary = args.port_file + ".tmp"
    with open(temporary, "w", encoding="utf-8") as f:
        f.write(f"{server.server_address[1]}\n")
    os.rename(temporary, args.port_file)
    server.serve_forever()


if __name__ == "__main__":
    main()
