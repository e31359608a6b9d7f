#!/usr/bin/env bash
# `pathlab view` in headless Chromium: starts a server on a free port, drives
# the page (view.test.mjs), which ends by stopping the server through its API.
#   run_view_test.sh PATHLAB ARTIFACT_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
pathlab=$1 artifacts=$2

# playwright-core exactly as locked; it never downloads a browser.
if [[ ! -f "$here/node_modules/playwright-core/package.json" ]]; then
  (cd "$here" && npm ci --no-audit --no-fund --loglevel=error)
fi
mkdir -p "$artifacts"

out=$(mktemp) reference=$(mktemp --suffix=.exr)
"$pathlab" render --scene cornell-box --size 96x96 --max-depth 4 --sampler sobol-owen --spp 256 \
  -o "$reference" 2>/dev/null
"$pathlab" view --scene cornell-box --size 96x96 --max-depth 4 --sampler independent \
  --compare sobol-owen --reference "$reference" --max-spp 4096 --port 0 --threads 1 >"$out" &
server=$!
trap 'kill "$server" 2>/dev/null || true; rm -f "$out" "$reference"' EXIT
for _ in $(seq 100); do
  url=$(grep -o 'http://[^ ]*' "$out" || true)
  [[ -n "$url" ]] && break
  sleep 0.1
done
[[ -n "$url" ]] || { echo "pathlab view printed no URL" >&2; exit 1; }
# The test ends by POST /api/stop: the server must then exit with code 0.
node "$here/view.test.mjs" "$url" "$artifacts"
wait "$server"
