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
# Another renderer's images beside pathlab's: pathlab itself at depth 1 (direct
# light only), which is too dark everywhere, so the report must flag it biased.
for sampler in independent sobol-owen; do
  mkdir -p "$work/direct/$sampler"
  for spp in 1 2 4 8; do
    for seed in 0 1; do
      "$pathlab" render --scene cornell-box --sampler "$sampler" --spp "$spp" --seed "$seed" \
        --size 48x48 --max-depth 1 -o "$work/direct/$sampler/spp$spp-seed$seed.exr" 2>/dev/null
    done
  done
done
cat >>"$work/spec.toml" <<'SPEC'

[[external]]
name = "direct"
scene = "cornell-box"
images = "direct/{sampler}/spp{spp}-seed{seed}.exr"
SPEC
"$pathlab" study "$work/spec.toml" -o "$work/study" --resume
"$pathlab" report "$work/study"
node "$here/report.test.mjs" "$work/study/report/index.html" "$artifacts"
