#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The HTTP endpoints over mutual TLS, with the real server.
#   control_tls_test.sh BIN_DIR WORK_DIR
# openssl makes a CA, a server certificate and two client certificates (one
# the CA signed, one self-signed). The server serves the control API and
# /metrics over HTTPS on 0.0.0.0 with the CA as its client CA (mutual TLS
# lets /metrics leave loopback without bearer keys). Plain HTTP, TLS without
# a client certificate and TLS with a foreign one get no answer; with the
# CA's client certificate, the control API still wants its bearer key (401
# without it, 201 with it) and a scrape is answered.
set -euo pipefail
bin=$1
work=$2
test_name=control_tls
# shellcheck source=script_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/script_common.sh"
enter_work_dir "$work"

command -v openssl >/dev/null || fail "openssl is missing (scripts/setup.sh installs it)"
subject() { echo "/CN=$1"; }
openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj "$(subject rewind-test-ca)" \
  -keyout ca.key -out ca.pem 2>/dev/null
for name in https client; do
  openssl req -newkey rsa:2048 -nodes -subj "$(subject "$name")" -keyout "$name.key" \
    -out "$name.csr" 2>/dev/null
  printf 'subjectAltName=IP:127.0.0.1\n' >"$name.ext"
  openssl x509 -req -in "$name.csr" -CA ca.pem -CAkey ca.key -CAcreateserial -days 2 \
    -extfile "$name.ext" -out "$name.pem" 2>/dev/null
done
openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj "$(subject intruder)" \
  -keyout intruder.key -out intruder.pem 2>/dev/null

"$bin/rewind-token" keygen --out server.key >/dev/null
key=$("$bin/rewind-token" api-key --name backend --keys control.keys)
"$bin/rewind-server" --bind 127.0.0.1 --port 0 --matches 0 --control \
  --control-bind 0.0.0.0:0 --control-port-file cport --control-keys control.keys \
  --metrics-bind 0.0.0.0:0 --metrics-port-file mport --key-file server.key \
  --http-tls-cert https.pem --http-tls-key https.key --http-tls-client-ca ca.pem \
  >server.json 2>server.log &
server_pid=$!
pids+=("$server_pid")
for _ in $(seq 1 100); do [ -s cport ] && [ -s mport ] && break; sleep 0.1; done
[ -s cport ] || fail "no control endpoint: $(cat server.log)"
log_has server.log "control API on https://" || fail "no https in the log: $(cat server.log)"
log_has server.log "mutual TLS" || fail "the log does not say mutual TLS: $(cat server.log)"

# call PORT METHOD TARGET CERT KEY: prints the status code, or "none" when
# the connection ends without an answer.
call() {
  python3 - "$@" <<'PY'
import http.client, ssl, sys
port, method, target, cert, key = sys.argv[1:6]
bearer = sys.argv[6] if len(sys.argv) > 6 else ""
try:
    if cert == "plain":
        connection = http.client.HTTPConnection("127.0.0.1", int(port), timeout=5)
    else:
        context = ssl.create_default_context(cafile="ca.pem")
        if cert != "none":
            context.load_cert_chain(cert, key)
        connection = http.client.HTTPSConnection("127.0.0.1", int(port), timeout=5,
                                                 context=context)
    headers = {"Authorization": f"Bearer {bearer}"} if bearer else {}
    connection.request(method, target, headers=headers)
    print(connection.getresponse().status)
except (ssl.SSLError, ConnectionError, http.client.HTTPException, OSError):
    print("none")
PY
}
cport=$(cat cport)
mport=$(cat mport)
[ "$(call "$cport" GET /matches plain - "$key")" = none ] || fail "plain HTTP got an answer"
[ "$(call "$cport" GET /matches none - "$key")" = none ] || fail "TLS without a certificate got an answer"
[ "$(call "$cport" GET /matches intruder.pem intruder.key "$key")" = none ] ||
  fail "a foreign certificate got an answer"
[ "$(call "$cport" GET /matches client.pem client.key)" = 401 ] || fail "no bearer key was not 401"
[ "$(call "$cport" POST "/matches?id=tls-1" client.pem client.key "$key")" = 201 ] ||
  fail "the CA's client with its key was not served"
[ "$(call "$mport" GET /metrics client.pem client.key)" = 200 ] || fail "the scrape was not served"
[ "$(call "$mport" GET /metrics none -)" = none ] || fail "a scrape without a certificate got an answer"
kill -TERM "$server_pid"
wait "$server_pid" || fail "server exited with $? after SIGTERM: $(tail -5 server.log)"
echo "PASS [control_tls]: plain, certificate-less and foreign clients refused; the CA's client served"
