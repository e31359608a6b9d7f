#!/usr/bin/env bash
# Side-by-side throughput of pathlab and Embree's tutorial path tracer
# (Debian embree-tools, `pathtracer`) on the Cornell box: 512×512, 16 spp,
# maximum path length 8, same camera, pathlab without Russian roulette. The two
# alternate RUNS times; the ratio of paths/s is taken from whole-process wall
# time and the median is reported.
#
# usage: bench/vs_embree.sh [RUNS] [PATHLAB_BINARY]
set -euo pipefail
runs=${1:-5}
pathlab=${2:-build/release/pathlab}
models=/usr/share/doc/embree3/models
command -v pathtracer >/dev/null || { echo "vs_embree: install embree-tools" >&2; exit 2; }
[[ -x $pathlab ]] || { echo "vs_embree: build pathlab first ($pathlab)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
paths=$((512 * 512 * 16))

seconds() {  # wall time of a command, in seconds
    local start end
    start=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    end=$(date +%s.%N)
    echo "$end - $start" | bc -l
}

ratios=()
for ((i = 1; i <= runs; ++i)); do
    # Embree's tutorial reads the camera and point light from cornell_box.ecs.
    te=$(cd "$models" && seconds pathtracer -c cornell_box.ecs --size 512 512 --spp 16 \
        --max-path-length 8 -o "$work/embree.ppm")
    tp=$(seconds "$pathlab" render --scene cornell-box --size 512x512 --spp 16 --max-depth 8 \
        --no-russian-roulette -o "$work/pathlab.exr")
    ratio=$(echo "$te / $tp" | bc -l)
    ratios+=("$ratio")
    printf 'run %d: embree %.3f s (%.3g paths/s), pathlab %.3f s (%.3g paths/s), ratio %.3f\n' \
        "$i" "$te" "$(echo "$paths / $te" | bc -l)" "$tp" "$(echo "$paths / $tp" | bc -l)" "$ratio"
done
median=$(printf '%s\n' "${ratios[@]}" | sort -g | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}')
printf 'median ratio of paths/s (pathlab / embree pathtracer): %.3f over %d runs\n' "$median" "$runs"
