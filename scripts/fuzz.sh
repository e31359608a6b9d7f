#!/usr/bin/env bash
# Runs every libFuzzer target of a fuzz build for a bounded time each:
#   scripts/fuzz.sh BUILD_DIR SECONDS TARGET...
# Each starts from the committed seeds in fuzz/corpus/<target>/ plus what
# earlier runs found (BUILD_DIR/corpus/<target>/, never committed). A crash,
# sanitizer report, leak, timeout or out-of-memory fails the run; the input
# that caused it is saved as BUILD_DIR/artifacts/<target>-crash-… and the end
# of the fuzzer's log is printed. Every target runs even when one fails.
set -uo pipefail
cd "$(dirname "$0")/.."
build=$1 seconds=$2
shift 2
mkdir -p "$build/artifacts" "$build/logs"
failed=()
for target in "$@"; do
  mkdir -p "$build/corpus/$target"
  log="$build/logs/$target.log"
  start=$(date +%s)
  "$build/fuzz_$target" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" \
    "$build/corpus/$target" "fuzz/corpus/$target" >"$log" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  if [[ $rc -eq 0 ]]; then
    echo "fuzz $target: ok, ${runs:-?} runs in $(($(date +%s) - start)) s"
  else
    echo "fuzz $target: FAILED (exit $rc), log $log:" >&2
    tail -n 40 "$log" >&2
    failed+=("$target")
  fi
done
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "fuzz: failures in ${failed[*]} (inputs in $build/artifacts/)" >&2
  exit 1
fi
