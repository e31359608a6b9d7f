#!/usr/bin/env bash
# Parallel efficiency of a study across MPI ranks (docs/cluster.md,
# "Measured"): the same study as 1 process × 2 threads and as 2 ranks × 1
# thread on one two-core host.
#
#   bench/mpi_scaling.sh [PATHLAB] [PRESET] [MODE]   (defaults: build/release/pathlab seed cold)
#
# MODE cold: each run starts from an empty reference cache, so it renders the
# references too, in sample ranges shared among the ranks — the whole study.
# MODE cached: both runs find the references in a warm cache; what is
# compared is the cell phase alone (the schedule, the messages, rank 0's
# commits).
#
# Efficiency = T(1 process × 2 threads) / T(2 ranks × 1 thread). Run it on a
# quiet machine: other work on the cores shows up as lost efficiency, so the
# load average is printed with the figures.
set -euo pipefail
PATHLAB=${1:-build/release/pathlab}
PRESET=${2:-seed}
MODE=${3:-cold}
case "$MODE" in cold | cached) ;; *) echo "mode must be cold or cached, got '$MODE'" >&2; exit 2 ;; esac
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

seconds() {  # wall seconds of a command, its output to $WORK/log
  local start end
  start=$(date +%s.%N)
  "$@" >"$WORK/log" 2>&1 || { cat "$WORK/log" >&2; exit 1; }
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { print b - a }'
}

cache() {  # the cache a run uses: its own empty one when cold
  if [ "$MODE" = cold ]; then echo "$WORK/cache-$1"; else echo "$WORK/cache"; fi
}

if [ "$MODE" = cached ]; then
  echo "warming the reference cache ($PRESET)..." >&2
  PATHLAB_CACHE=$(cache warm) seconds "$PATHLAB" study --preset "$PRESET" -o "$WORK/warm" \
    --threads 2 >/dev/null
fi
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
one=$(PATHLAB_CACHE=$(cache one) seconds "$PATHLAB" study --preset "$PRESET" -o "$WORK/one" \
  --threads 2)
two=$(PATHLAB_CACHE=$(cache two) seconds mpirun --oversubscribe --bind-to none -np 2 \
  -x PATHLAB_CACHE "$PATHLAB" study --preset "$PRESET" -o "$WORK/two" --threads 1)
printf 'preset %s, references %s, on %s (load before %s, after %s)\n' "$PRESET" \
  "$([ "$MODE" = cold ] && echo rendered || echo cached)" "$(hostname)" "$load_before" \
  "$(cut -d' ' -f1-3 /proc/loadavg)"
printf '1 process x 2 threads: %8.2f s\n2 ranks x 1 thread:    %8.2f s\nefficiency: %.1f%%\n' \
  "$one" "$two" "$(awk -v a="$one" -v b="$two" 'BEGIN { print 100 * a / b }')"
