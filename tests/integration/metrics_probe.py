#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""HTTP helpers for tests/integration/metrics_test.sh (standard library only).

  get    PORT PATH        GET http://127.0.0.1:PORT/PATH; prints the status line
                          "HTTP <code>" and then the body. Exit 0 whatever the code.
  status PORT PATH        Only the status code of that GET.
  value  PORT NAME        The value of sample NAME in a scrape of /metrics: the
                          series NAME itself, or the first NAME{...} series.
  query  PROM_PORT EXPR   An instant query to Prometheus's HTTP API; prints one line
                          per result, "labels value", nothing when there is none.
  hostile PORT DEADLINE_S Clients that never finish their request: one that stops
                          midway through its headers and 19 that say nothing, so
                          that some find the connection cap (16). Checks that a
                          scrape sent while they are held is answered (the oldest
                          unfinished connections give way), that the server
                          closes every one of them within the deadline (plus a
                          second) without answering any, and that /metrics
                          answers afterwards. Prints a JSON summary; exit 1 on
                          any failure.
  logs   FILE             Every line of FILE is a JSON object with "ts" (ISO 8601
                          UTC), "level" (info, warning, error) and "msg"; prints
                          how many. Exit 1 on the first that is not.
  free-port               A TCP port on 127.0.0.1 that was free a moment ago.
"""
import json
import re
import socket
import sys
import time
import urllib.error
import urllib.parse
import urllib.request


def get(port: int, path: str) -> tuple[int, str]:
    url = f"http://127.0.0.1:{port}{path}"
    try:
        with urllib.request.urlopen(url, timeout=5) as response:
            return response.status, response.read().decode()
    except urllib.error.HTTPError as error:
        return error.code, error.read().decode()


def metric_value(port: int, name: str) -> str:
    status, body = get(port, "/metrics")
    if status != 200:
        return ""
    for line in body.splitlines():
        if line.startswith(name + " ") or line.startswith(name + "{"):
            return line.rsplit(" ", 1)[1]
    return ""


def query(port: int, expr: str) -> list[str]:
    url = f"http://127.0.0.1:{port}/api/v1/query?" + urllib.parse.urlencode({"query": expr})
    with urllib.request.urlopen(url, timeout=5) as response:
        answer = json.load(response)
    if answer.get("status") != "success":
        raise RuntimeError(f"query {expr}: {answer}")
    lines = []
    for result in answer["data"]["result"]:
        labels = ",".join(f'{k}="{v}"' for k, v in sorted(result["metric"].items()))
        lines.append(f"{{{labels}}} {result['value'][1]}")
    return lines


def closed_within(sock: socket.socket, seconds: float) -> tuple[bool, bytes]:
    """Reads until the server closes; False if it is still open after `seconds`."""
    sock.settimeout(seconds)
    data = b""
    try:
        while True:
            chunk = sock.recv(4096)
            if not chunk:
                return True, data
            data += chunk
    except ConnectionResetError:
        return True, data
    except socket.timeout:
        return False, data


def hostile(port: int, deadline_s: float) -> int:
    failures = []
    start = time.monotonic()
    partial = socket.create_connection(("127.0.0.1", port))
    partial.sendall(b"GET /metrics HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
    silent = [socket.create_connection(("127.0.0.1", port)) for _ in range(19)]
    status, _ = get(port, "/metrics")
    if status != 200:
        failures.append(f"a scrape among held connections got {status}")
    early = 0
    for sock in [partial] + silent:
        # Never a negative wait (settimeout refuses one) when the machine is slow.
        closed, data = closed_within(sock, max(0.05, deadline_s + 1.0 - (time.monotonic() - start)))
        if not closed:
            failures.append("a connection outlived the deadline")
        elif data and not data.startswith(b"HTTP/1.1 503"):
            failures.append(f"an unfinished request got an answer: {data[:40]!r}")
        if time.monotonic() - start < deadline_s * 0.5:
            early += 1
        sock.close()
    held_s = time.monotonic() - start
    if early < 19 + 1 + 1 - 16:
        failures.append(f"only {early} held connections gave way to newer ones")
    status, _ = get(port, "/metrics")
    if status != 200:
        failures.append(f"/metrics answers {status} afterwards")
    print(json.dumps({"held_s": round(held_s, 2), "gave_way": early, "failures": failures}))
    return 1 if failures else 0


LOG_TS = re.compile(r"^\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}\.\d{3}Z$")


def check_logs(path: str) -> int:
    count = 0
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        try:
            entry = json.loads(line)
            ok = (isinstance(entry, dict) and set(entry) == {"ts", "level", "msg"}
                  and LOG_TS.match(entry["ts"]) is not None
                  and entry["level"] in ("info", "warning", "error")
                  and isinstance(entry["msg"], str))
        except json.JSONDecodeError:
            ok = False
        if not ok:
            print(f"line {number} is not a JSON log line: {line!r}")
            return 1
        count += 1
    print(count)
    return 0 if count > 0 else 1


def main() -> int:
    args = sys.argv[1:]
    if len(args) == 3 and args[0] == "get":
        status, body = get(int(args[1]), args[2])
        print(f"HTTP {status}")
        print(body, end="")
        return 0
    if len(args) == 3 and args[0] == "status":
        print(get(int(args[1]), args[2])[0])
        return 0
    if len(args) == 3 and args[0] == "value":
        print(metric_value(int(args[1]), args[2]))
        return 0
    if len(args) == 3 and args[0] == "query":
        for line in query(int(args[1]), args[2]):
            print(line)
        return 0
    if len(args) == 3 and args[0] == "hostile":
        return hostile(int(args[1]), float(args[2]))
    if len(args) == 2 and args[0] == "logs":
        return check_logs(args[1])
    if len(args) == 1 and args[0] == "free-port":
        with socket.socket() as sock:
            sock.bind(("127.0.0.1", 0))
            print(sock.getsockname()[1])
        return 0
    print(__doc__, file=sys.stderr)
    return 64


if __name__ == "__main__":
    sys.exit(main())
