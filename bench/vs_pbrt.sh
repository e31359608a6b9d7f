#!/usr/bin/env bash
# The Cornell box's sampler comparison (docs/samplers.md) rendered by pbrt-v4
# instead of pathlab: the same scene (bench/pbrt/cornell-box.pbrt), 256×256,
# maximum depth 8, pbrt-v4's path integrator (next-event estimation, MIS,
# Russian roulette after two bounces, as pathlab's default). For each of
# pbrt-v4's samplers named below, at 1, 16 and 256 spp and seeds 0, 1, 2, it
# prints the MSE ratio to `independent` with the reference's noise taken out:
#     ratio = (MSE(sampler) − F) / (MSE(independent) − F).
# The reference A is a 1024-spp `paddedsobol` render (seed 1000); a second one,
# B (seed 1001), is independent of it, so MSE(A, B) = 2F and F = MSE(A, B)/2
# is A's own error. MSEs are measured by `pathlab compare`.
#
# pbrt-v4 is not a Debian package: build it from https://github.com/mmp/pbrt-v4
# and pass its binary. About 25 minutes on two cores per filter; the script
# keeps finished renders in OUTDIR and resumes where it stopped.
#
# usage: bench/vs_pbrt.sh PBRT_BINARY [FILTER=box|gaussian] [OUTDIR] [PATHLAB_BINARY]
set -euo pipefail
if (($# < 1)); then
    echo "usage: bench/vs_pbrt.sh PBRT_BINARY [box|gaussian] [OUTDIR] [PATHLAB_BINARY]" >&2
    exit 2
fi
pbrt=$1
filter=${2:-box}
out=${3:-vs-pbrt-$filter}
pathlab=${4:-build/release/pathlab}
samplers=(independent sobol zsobol paddedsobol halton)
spps=(1 16 256)
[[ -x $pbrt ]] || { echo "vs_pbrt: not an executable: $pbrt" >&2; exit 2; }
[[ -x $pathlab ]] || { echo "vs_pbrt: build pathlab first ($pathlab)" >&2; exit 2; }
[[ $filter == box || $filter == gaussian ]] || { echo "vs_pbrt: filter must be box or gaussian, got '$filter'" >&2; exit 2; }
world=$(cd "$(dirname "$0")/pbrt" && pwd)/cornell-box.pbrt
mkdir -p "$out"
trap 'rm -f "$out"/*.part.pfm' EXIT  # an interrupted render leaves no file behind

# pbrt-v4's camera space is left-handed: Scale −1 1 1 puts world +x, and so
# the red wall, on the image's left, as in pathlab's image.
scene() {  # SAMPLER → scene file
    local file="$out/$1.pbrt"
    cat >"$file" <<EOF
Scale -1 1 1
LookAt 278 273 -800  278 273 0  0 1 0
Camera "perspective" "float fov" 37.5
Film "rgb" "integer xresolution" 256 "integer yresolution" 256 "string filename" "unused.exr"
PixelFilter "$filter"
Sampler "$1"
Integrator "path" "integer maxdepth" 8
WorldBegin
Include "$world"
EOF
    echo "$file"
}

render() {  # SAMPLER SPP SEED OUTPUT; kept when already there (the script resumes)
    [[ -s $4 ]] && return
    "$pbrt" --quiet --nthreads "$(nproc)" --spp "$2" --seed "$3" --outfile "$4.part.pfm" \
        "$(scene "$1")" >/dev/null
    mv "$4.part.pfm" "$4"
}

mse() {  # REFERENCE TEST
    "$pathlab" compare --metric mse --json "$1" "$2" | sed -E 's/.*"mse": *([^,}]*).*/\1/'
}

render paddedsobol 1024 1000 "$out/reference-a.pfm"
render paddedsobol 1024 1001 "$out/reference-b.pfm"
calc() { awk "BEGIN { printf \"%.10g\", $1 }"; }  # arithmetic on e-notation figures
floor=$(calc "$(mse "$out/reference-a.pfm" "$out/reference-b.pfm") / 2")
for s in "${samplers[@]}"; do
    for n in "${spps[@]}"; do
        for seed in 0 1 2; do render "$s" "$n" "$seed" "$out/$s-spp$n-seed$seed.pfm"; done
    done
done

mean_mse() {  # SAMPLER SPP → the mean MSE over the seeds
    local sum=0
    for seed in 0 1 2; do sum=$(calc "$sum + $(mse "$out/reference-a.pfm" "$out/$1-spp$2-seed$seed.pfm")"); done
    calc "$sum / 3"
}
printf 'pbrt-v4, Cornell box 256x256, depth 8, %s filter, 3 seeds; reference noise F = %.3g\n' "$filter" "$floor"
printf '%-12s' sampler; for n in "${spps[@]}"; do printf '%10s' "$n spp"; done; echo
declare -A independent
for n in "${spps[@]}"; do independent[$n]=$(mean_mse independent "$n"); done
for s in "${samplers[@]}"; do
    printf '%-12s' "$s"
    for n in "${spps[@]}"; do
        printf '%10.3f' "$(calc "($(mean_mse "$s" "$n") - $floor) / (${independent[$n]} - $floor)")"
    done
    echo
done
printf 'independent MSE:'; for n in "${spps[@]}"; do printf ' %.3g (%s spp)' "${independent[$n]}" "$n"; done; echo
