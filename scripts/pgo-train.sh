#!/usr/bin/env bash
# The training run of pathlab's profile-guided build (Makefile, PGO=1): the
# instrumented binary renders both built-in scenes once with every sampler, at a
# small size, so the profile sees the integrator, the lights, the BSDFs and each
# sampler's hot loop the way a study does. The images are thrown away.
# Usage: scripts/pgo-train.sh INSTRUMENTED_PATHLAB
set -euo pipefail
pathlab=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export PATHLAB_CACHE="$work/cache"

scenes=(cornell-box)
# The wolf needs its meshes; without them the profile covers the Cornell box only.
if "$pathlab" render --scene wolf --size 8x8 --spp 1 -o "$work/probe.exr" >/dev/null 2>&1; then
  scenes+=(wolf)
fi
for scene in "${scenes[@]}"; do
  for sampler in $("$pathlab" samplers | awk 'NR > 1 { print $1 }'); do
    "$pathlab" render --scene "$scene" --sampler "$sampler" --size 64x64 --spp 64 \
      -o "$work/$scene-$sampler.exr" >/dev/null
  done
done
echo "profile trained on: ${scenes[*]}"
