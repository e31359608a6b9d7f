#!/usr/bin/env bash
# How screen-space samplers spread their error, spp by spp (docs/samplers.md,
# "sobol-bluenoise's error spectrum"): the low-frequency error fraction
# (`pathlab compare --error-spectrum`: the error's power below a quarter of
# Nyquist over its total, π/64 ≈ 0.049 for white noise) at 1, 2, 4, …, 256
# spp for independent, sobol-owen, zsobol, blue-noise and sobol-bluenoise, on
# bench/scenes/lit-plane.json (depth 1) and the Cornell box (depth 8), both
# 128×128, mean of SEEDS seeds; and each sampler's MSE over sobol-owen's.
# References: sobol-owen at REF_SPP (4096) spp, another seed.
#
# usage: [REF_SPP=…] [SEEDS="1 2"] [SAMPLERS="sobol-owen …"] [SPPS="1 2 … 256"] [SCENES="lit-plane cornell-box"] bench/sobol_bluenoise_spectrum.sh
#        [PATHLAB=build/release/pathlab] [OUTDIR=sobol-bluenoise-spectrum]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
pathlab=${1:-$root/build/release/pathlab}
out=${2:-sobol-bluenoise-spectrum}
[[ -x $pathlab ]] || { echo "sobol_bluenoise_spectrum: build pathlab first ($pathlab)" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
trap 'rm -f "$out"/*.part.pfm' EXIT
ref_spp=${REF_SPP:-4096}
seeds=${SEEDS:-1 2}
spps=${SPPS:-1 2 4 8 16 32 64 128 256}
samplers=${SAMPLERS:-sobol-owen independent zsobol blue-noise sobol-bluenoise}  # sobol-owen first: the MSE baseline

render() {  # SCENE DEPTH SAMPLER SPP SEED OUTPUT
    [[ -s $6 ]] && return
    "$pathlab" render --scene "$1" --max-depth "$2" --sampler "$3" --spp "$4" --seed "$5" \
        --size 128x128 --threads 2 -o "$6.part.pfm" 2>/dev/null
    mv "$6.part.pfm" "$6"
}
# "mse lowfreq" of TEST against REFERENCE.
measure() {
    local json
    json=$("$pathlab" compare --metric mse --json --error-spectrum "$out/spectrum.csv" "$1" "$2")
    echo "$(sed -E 's/.*"mse": *([^,}]*).*/\1/' <<<"$json")" \
        "$(sed -E 's/.*"low_frequency_fraction": *([^,}]*).*/\1/' <<<"$json")"
}

for scene in ${SCENES:-lit-plane cornell-box}; do
    case $scene in
        lit-plane) file=$root/bench/scenes/lit-plane.json depth=1 ;;
        cornell-box) file=cornell-box depth=8 ;;
    esac
    ref=$out/$scene-reference.pfm
    render "$file" "$depth" sobol-owen "$ref_spp" 1000 "$ref"
    echo "## $scene: low-frequency error fraction (MSE / sobol-owen's)"
    printf '%-16s' sampler
    for spp in $spps; do printf ' %13s' "$spp"; done
    echo
    declare -A owen_mse=()
    for sampler in $samplers; do
        line=$(printf '%-16s' "$sampler")
        for spp in $spps; do
            lf=0 mse=0
            for seed in $seeds; do
                img=$out/$scene-$sampler-$spp-$seed.pfm
                render "$file" "$depth" "$sampler" "$spp" "$seed" "$img"
                read -r m l <<<"$(measure "$ref" "$img")"
                lf=$(awk "BEGIN { print $lf + $l }") mse=$(awk "BEGIN { print $mse + $m }")
            done
            [[ $sampler == sobol-owen ]] && owen_mse[$spp]=$mse
            line+=$(awk "BEGIN { printf \" %6.3f (%4.2f)\", $lf / $(wc -w <<<"$seeds"), \
                $mse / ${owen_mse[$spp]} }")
        done
        echo "$line"
    done
    unset owen_mse
    echo
done
