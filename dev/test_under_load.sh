#!/usr/bin/env bash
# Runs the test command (scripts/setup_and_test.sh) RUNS times in a row (default 3) while one busy
# loop per core loads the machine: the proof that no test depends on the machine's speed.
# Prints each run's "N passed, N failed, N skipped" line and wall time; exit 0 only if
# every run passed.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
runs="${1:-3}"
loops=()
for _ in $(seq "$(nproc)"); do
  timeout 7200 sh -c 'while :; do :; done' &
  loops+=("$!")
done
trap 'kill "${loops[@]}" 2>/dev/null' EXIT
status=0
for i in $(seq "$runs"); do
  start=$(date +%s)
  log="$(mktemp /tmp/bearing_sim_test_under_load.XXXXXX)"
  "$here/../scripts/setup_and_test.sh" > "$log" 2>&1 || status=1
  echo "run $i: $(tail -1 "$log") in $(( $(date +%s) - start )) s, load average $(cut -d' ' -f1-3 /proc/loadavg) (log: $log)"
done
exit "$status"
