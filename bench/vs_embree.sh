#!/usr/bin/env bash
# Side-by-side throughput of pathlab and Embree's tutorial path tracer
# (Debian embree-tools, `pathtracer`) on the Cornell box: 512×512, 16 spp,
# maximum path length 8, same camera, pathlab without Russian roulette. The two
# alternate RUNS times; the ratio of paths/s is taken from whole-process wall
# time and the median is reported. Last, each side's rays per frame: Embree's
# from the tutorial's own benchmark mode (its Mrays/s over its frames/s), ours
# from pathlab's summary line — the ratio of paths/s is a ratio of per-ray cost
# only when the two trace about as many rays.
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

# Rays per frame on each side.
bench=$(cd "$models" && pathtracer -c cornell_box.ecs --size 512 512 --spp 16 \
    --max-path-length 8 --benchmark 0 1 2>&1)
embree_fps=$(awk '/^BENCHMARK_RENDER_AVG /{print $2}' <<<"$bench")
embree_mrays=$(awk '/^BENCHMARK_RENDER_MRAYPS_AVG /{print $2}' <<<"$bench")
summary=$("$pathlab" render --scene cornell-box --size 512x512 --spp 16 --max-depth 8 \
    --no-russian-roulette -o "$work/pathlab.exr" 2>&1 | grep '^rendered')
pathlab_rays=$(sed -E 's/.* in ([0-9.]+) s: .* ([0-9.e+]+) rays\/s.*/\1 * \2/' <<<"$summary" |
    sed 's/e+/*10^/' | bc -l)
embree_rays=$(echo "$embree_mrays * 10^6 / $embree_fps" | bc -l)
printf 'rays per frame: embree %.3g (%.2f per path), pathlab %.3g (%.2f per path)\n' \
    "$embree_rays" "$(echo "$embree_rays / $paths" | bc -l)" \
    "$pathlab_rays" "$(echo "$pathlab_rays / $paths" | bc -l)"
