#!/usr/bin/env bash
# Spectral mode's cost: the Cornell box's paths/s in RGB and in spectral mode
# (`pathlab render --spectral`), alternating the two modes run by run so that
# both see the same machine load, and the ratio of their medians. The
# renders are pathlab's defaults otherwise: maximum depth 8, Russian
# roulette, the `independent` sampler.
#
# usage: bench/spectral_speed.sh [PATHLAB_BINARY] [RUNS=5] [SIZE=256] [SPP=16]
set -euo pipefail
pathlab=${1:-build/release/pathlab}
runs=${2:-5}
size=${3:-256}
spp=${4:-16}
[[ -x $pathlab ]] || { echo "spectral_speed: build pathlab first ($pathlab)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

rate() {  # extra options… → paths/s of one render
    "$pathlab" render --scene cornell-box --sampler independent --spp "$spp" \
        --size "${size}x${size}" "$@" -o "$out/image.exr" 2>&1 |
        sed -n 's/.* s: \([0-9.e+]*\) paths\/s.*/\1/p'
}

rgb=() spectral=()
for ((i = 0; i < runs; ++i)); do
    rgb+=("$(rate)")
    spectral+=("$(rate --spectral)")
done
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
echo "rgb paths/s:      ${rgb[*]}"
echo "spectral paths/s: ${spectral[*]}"
m1=$(median "${rgb[@]}") m2=$(median "${spectral[@]}")
awk -v a="$m1" -v b="$m2" 'BEGIN {printf "median rgb %.3g, spectral %.3g paths/s: spectral/rgb = %.2f\n", a, b, b / a}'
