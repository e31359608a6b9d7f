#!/usr/bin/env bash
# Light selection strategies measured (docs/rendering.md, "Choosing a light"):
# for uniform, power and bvh, pathlab's paths/s on scenes/pbrt/many-lights.pbrt
# (200 lights) and on the same scene with only its first 4 lights, and the MSE
# of a 16-spp render of the 200-light scene against a 1024-spp bvh reference
# (its own noise taken out: a second reference of another seed gives
# F = MSE(A, B)/2, and the table shows MSE − F). 320×240, zsobol, depth 5,
# 2 threads, as the scene file says; the timed renders at SPEED_SPP (64) spp,
# RUNS (3) times each, the best kept; references at REF_SPP (1024) spp.
#
# usage: [REF_SPP=…] [SPEED_SPP=…] [RUNS=…] bench/light_selection.sh [PATHLAB=build/release/pathlab] [OUTDIR=light-selection]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
pathlab=${1:-$root/build/release/pathlab}
out=${2:-light-selection}
[[ -x $pathlab ]] || { echo "light_selection: build pathlab first ($pathlab)" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
trap 'rm -f "$out"/*.part.pfm' EXIT
many=$root/scenes/pbrt/many-lights.pbrt
few=$out/four-lights.pbrt
ref_spp=${REF_SPP:-1024} speed_spp=${SPEED_SPP:-64} runs=${RUNS:-3}
"${PYTHON:-/usr/bin/python3}" "$root/scripts/make_many_lights.py" "$few" 4

# Best paths/s of three renders (the render's own figure: render phase only).
paths_per_second() {  # SCENE STRATEGY SPP OUTPUT
    local best=0 rate
    for ((run = 0; run < runs; ++run)); do
        rate=$("$pathlab" render --scene "$1" --light-sampler "$2" --spp "$3" --threads 2 \
            -o "$4.part.pfm" 2>&1 | sed -nE 's/.*: ([0-9.e+]+) paths\/s.*/\1/p')
        best=$(awk "BEGIN { print ($rate > $best) ? $rate : $best }")
    done
    mv "$4.part.pfm" "$4"
    echo "$best"
}
mse() { "$pathlab" compare --metric mse --json "$1" "$2" | sed -E 's/.*"mse": *([^,}]*).*/\1/'; }

for seed in 1000 1001; do
    [[ -s $out/reference-$seed.pfm ]] ||
        { "$pathlab" render --scene "$many" --light-sampler bvh --spp "$ref_spp" --seed "$seed" \
            --threads 2 -o "$out/reference.part.pfm" 2>/dev/null &&
            mv "$out/reference.part.pfm" "$out/reference-$seed.pfm"; }
done
floor=$(awk "BEGIN { print $(mse "$out/reference-1000.pfm" "$out/reference-1001.pfm") / 2 }")

printf '%-9s %18s %18s %8s %16s\n' strategy "paths/s 4 lights" "paths/s 200 lights" ratio "MSE 16 spp"
for s in uniform power bvh; do
    few_rate=$(paths_per_second "$few" "$s" "$speed_spp" "$out/four-$s.pfm")
    many_rate=$(paths_per_second "$many" "$s" "$speed_spp" "$out/many-$s.pfm")
    "$pathlab" render --scene "$many" --light-sampler "$s" --spp 16 --threads 2 \
        -o "$out/many16-$s.part.pfm" 2>/dev/null
    mv "$out/many16-$s.part.pfm" "$out/many16-$s.pfm"
    err=$(awk "BEGIN { printf \"%.4g\", $(mse "$out/reference-1000.pfm" "$out/many16-$s.pfm") - $floor }")
    printf '%-9s %18.3g %18.3g %8.2f %16s\n' "$s" "$few_rate" "$many_rate" \
        "$(awk "BEGIN { print $few_rate / $many_rate }")" "$err"
done
