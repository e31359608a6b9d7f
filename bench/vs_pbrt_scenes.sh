#!/usr/bin/env bash
# pbrt-v4 scene files rendered by pbrt-v4 and by pathlab, side by side
# (docs/pbrt-format.md): for each scene, both programs render the same file
# at SPP samples per pixel with 2 threads (their own converged images), and
# the script prints per-channel means, pathlab's relative difference per
# channel, the mean ꟻLIP (LDR) between the two images, and each program's
# render time and paths/s.
#
# pbrt-v4 is not a Debian package: build it from https://github.com/mmp/pbrt-v4
# in a scratch folder and pass its binary. Finished renders are kept in OUTDIR
# and reused.
#
# usage: bench/vs_pbrt_scenes.sh PBRT_BINARY [SPP=1024] [OUTDIR] [PATHLAB] [SCENE.pbrt...]
set -euo pipefail
if (($# < 1)); then
    echo "usage: bench/vs_pbrt_scenes.sh PBRT_BINARY [SPP] [OUTDIR] [PATHLAB] [SCENE.pbrt...]" >&2
    exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
pbrt=$1
spp=${2:-1024}
out=${3:-vs-pbrt-scenes}
pathlab=${4:-$root/build/release/pathlab}
shift $(($# < 4 ? $# : 4))
scenes=("$@")
if ((${#scenes[@]} == 0)); then
    scenes=("$root/scenes/cornell-box.pbrt" "$root"/scenes/pbrt/*.pbrt)
fi
[[ -x $pbrt ]] || { echo "vs_pbrt_scenes: not an executable: $pbrt" >&2; exit 2; }
[[ -x $pathlab ]] || { echo "vs_pbrt_scenes: build pathlab first ($pathlab)" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
# envmap-sun.pbrt's sky is generated, not committed.
[[ -f $root/scenes/pbrt/sky-sun.pfm ]] ||
    "${PYTHON:-/usr/bin/python3}" "$root/scripts/make_sky_sun.py" "$root/scenes/pbrt/sky-sun.pfm"
[[ -f $root/scenes/pbrt/bump-normal-heights.png ]] ||
    "${PYTHON:-/usr/bin/python3}" "$root/scripts/make_bump_maps.py" "$root/scenes/pbrt"
[[ -f $root/scenes/pbrt/textured-bricks.png ]] ||
    "${PYTHON:-/usr/bin/python3}" "$root/scripts/make_texture_png.py" \
        "$root/scenes/pbrt/textured-bricks.png"
trap 'rm -f "$out"/*.part.pfm' EXIT

seconds() { local t0=$1 t1=$2; awk "BEGIN { printf \"%.3f\", $t1 - $t0 }"; }
now() { date +%s.%N; }

# Per-channel means of a PFM image (python3-numpy, installed by scripts/setup.sh).
means() {
    "${PYTHON:-/usr/bin/python3}" - "$1" <<'PY'
import sys, numpy as np
with open(sys.argv[1], 'rb') as f:
    kind = f.readline().strip(); w, h = map(int, f.readline().split()); scale = float(f.readline())
    data = np.frombuffer(f.read(), dtype='<f4' if scale < 0 else '>f4')
img = data.reshape(h, w, 3 if kind == b'PF' else 1)
print(' '.join('%.6g' % m for m in img.reshape(-1, img.shape[2]).mean(axis=0)))
PY
}

printf '%-16s %-24s %-24s %-22s %7s %16s %16s\n' scene "pbrt-v4 mean RGB" "pathlab mean RGB" \
    "difference R G B (%)" FLIP "pbrt paths/s" "pathlab paths/s"
# The film's x or y resolution (pbrt-v4's default when not given), read with
# comments stripped: scenes keep alternative resolutions commented out.
film_resolution() {
    local value
    value=$(sed 's/#.*//' "$1" | grep -o "$2"'resolution" *\[* *[0-9]*' | head -n 1 |
        grep -o '[0-9]*$' || true)
    echo "${value:-$3}"
}

for scene in "${scenes[@]}"; do
    name=$(basename "$scene" .pbrt)
    dir=$(dirname "$scene")
    a="$out/$name-pbrt.pfm" b="$out/$name-pathlab.pfm"
    size=$(film_resolution "$scene" x 1280)
    ysize=$(film_resolution "$scene" y 720)
    paths=$((size * ysize * spp))
    if [[ ! -s $a ]]; then
        t0=$(now)
        (cd "$dir" && "$pbrt" --quiet --nthreads 2 --spp "$spp" --outfile "$a.part.pfm" \
            "$(basename "$scene")") >/dev/null
        t1=$(now); mv "$a.part.pfm" "$a"; echo "$(seconds "$t0" "$t1")" >"$a.seconds"
    fi
    if [[ ! -s $b ]]; then
        t0=$(now)
        "$pathlab" render --scene "$scene" --spp "$spp" --threads 2 -o "$b.part.pfm" 2>/dev/null
        t1=$(now); mv "$b.part.pfm" "$b"; echo "$(seconds "$t0" "$t1")" >"$b.seconds"
    fi
    read -r ar ag ab <<<"$(means "$a")"
    read -r br bg bb <<<"$(means "$b")"
    flip=$("$pathlab" compare --metric flip --ldr --json "$a" "$b" | sed -E 's/.*"mean": *([^,}]*).*/\1/')
    diff=$(awk "BEGIN { printf \"%+.2f %+.2f %+.2f\", 100*($br/$ar-1), 100*($bg/$ag-1), 100*($bb/$ab-1) }")
    rate() { awk "BEGIN { printf \"%.3g\", $paths / $(cat "$1.seconds") }"; }
    printf '%-16s %-24s %-24s %-22s %7.4f %16s %16s\n' "$name" "$ar $ag $ab" "$br $bg $bb" "$diff" \
        "$flip" "$(rate "$a")" "$(rate "$b")"
done
