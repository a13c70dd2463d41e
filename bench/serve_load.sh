#!/usr/bin/env bash
# Load benchmark of `specula serve`: starts the server on a free loopback port, runs wrk against
# POST /api/eval and POST /api/albedo (DURATION seconds each, CONNECTIONS connections on THREADS
# threads), prints wrk's summary with latency percentiles and errors, and stops the server.
# Usage: bench/serve_load.sh [path/to/specula]   (default: build/release/specula)
# Environment: DURATION (10), CONNECTIONS (8), THREADS (2).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
specula=${1:-$here/../build/release/specula}
duration=${DURATION:-10}
connections=${CONNECTIONS:-8}
threads=${THREADS:-2}
command -v wrk >/dev/null || { echo "serve_load: wrk is missing (scripts/install-deps installs it)" >&2; exit 2; }
[ -x "$specula" ] || { echo "serve_load: no specula at $specula (make build)" >&2; exit 2; }

out=$(mktemp)
"$specula" serve --port 0 >"$out" &
server=$!
trap 'kill -TERM $server 2>/dev/null; wait $server 2>/dev/null; rm -f "$out"' EXIT
for _ in $(seq 100); do grep -q '^serving ' "$out" && break; sleep 0.05; done
url=$(sed -n 's/^serving //p' "$out")
[ -n "$url" ] || { echo "serve_load: the server did not start" >&2; exit 1; }

run() {  # name, path, body
  echo "== $1: POST $2 $3"
  echo "   ($connections connections, $threads threads, ${duration} s)"
  BODY=$3 wrk --latency -t"$threads" -c"$connections" -d"${duration}s" -s "$here/serve_post.lua" "${url%/}$2" \
    | grep -E 'Requests/sec|Transfer/sec|requests:|latency percentiles|Non-2xx|Socket errors'
}

run "eval, 100 cosines of log-normalized" /api/eval \
  '{"model": "log-normalized", "params": {"n": 50}, "cos": "0:1@100"}'
run "eval, 90 directions of ggx" /api/eval \
  '{"model": "ggx", "params": {"alpha": 0.2}, "theta_i": 30, "theta_o": "0:89@90", "phi_o": 180}'
run "albedo, 12 angles of log-normalized" /api/albedo \
  '{"model": "log-normalized", "params": {"n": 20}, "theta": "0:80:10,85,89"}'
run "albedo, 12 angles of ggx (a full BRDF: 2-D cubature)" /api/albedo \
  '{"model": "ggx", "params": {"alpha": 0.2}, "theta": "0:80:10,85,89"}'
