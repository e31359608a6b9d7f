#!/usr/bin/env bash
# The report's end-to-end test: a tiny study, `pathlab report`, then the page
# driven in headless Chromium (report.test.mjs).
#   run_report_test.sh PATHLAB WORK_DIR ARTIFACT_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
pathlab=$1 work=$2 artifacts=$3

# playwright-core exactly as locked; it never downloads a browser.
if [[ ! -f "$here/node_modules/playwright-core/package.json" ]]; then
  (cd "$here" && npm ci --no-audit --no-fund --loglevel=error)
fi

rm -rf "$work"
mkdir -p "$work" "$artifacts"
cat >"$work/spec.toml" <<'SPEC'
name = "report-test"
scenes = ["cornell-box"]
samplers = ["standard", "independent", "halton-rd"]
spp = [1, 2, 4, 8]
seeds = 2
resolution = [48, 48]

[reference]
spp = 64
SPEC
"$pathlab" study "$work/spec.toml" -o "$work/study"
"$pathlab" report "$work/study"
node "$here/report.test.mjs" "$work/study/report/index.html" "$artifacts"
