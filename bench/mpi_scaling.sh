#!/usr/bin/env bash
# Parallel efficiency of a study across MPI ranks (docs/cluster.md,
# "Measured"): the same study as 1 process × 2 threads and as 2 ranks × 1
# thread on one two-core host. Both runs find the references in a warm cache,
# so what is compared is the cell phase (the dynamic schedule, the messages,
# rank 0's commits), not the references, which rank 0 renders alone.
#
#   bench/mpi_scaling.sh [PATHLAB] [PRESET]      (defaults: build/release/pathlab seed)
#
# Efficiency = T(1 process × 2 threads) / T(2 ranks × 1 thread). Run it on a
# quiet machine: other work on the cores shows up as lost efficiency.
set -euo pipefail
PATHLAB=${1:-build/release/pathlab}
PRESET=${2:-seed}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export PATHLAB_CACHE=$WORK/cache
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

seconds() {  # wall seconds of a command, its output to $WORK/log
  local start end
  start=$(date +%s.%N)
  "$@" >"$WORK/log" 2>&1 || { cat "$WORK/log" >&2; exit 1; }
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { print b - a }'
}

echo "warming the reference cache ($PRESET)..." >&2
seconds "$PATHLAB" study --preset "$PRESET" -o "$WORK/warm" --threads 2 >/dev/null
one=$(seconds "$PATHLAB" study --preset "$PRESET" -o "$WORK/one" --threads 2)
two=$(seconds mpirun --oversubscribe --bind-to none -np 2 -x PATHLAB_CACHE \
  "$PATHLAB" study --preset "$PRESET" -o "$WORK/two" --threads 1)
printf 'preset %s, references cached, on %s (load %s)\n' "$PRESET" "$(hostname)" \
  "$(cut -d' ' -f1-3 /proc/loadavg)"
printf '1 process x 2 threads: %8.2f s\n2 ranks x 1 thread:    %8.2f s\nefficiency: %.1f%%\n' \
  "$one" "$two" "$(awk -v a="$one" -v b="$two" 'BEGIN { print 100 * a / b }')"
