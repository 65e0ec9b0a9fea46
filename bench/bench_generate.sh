#!/usr/bin/env bash
# Real-time factor per core of `bearing_tool generate` (docs/performance.md, docs/datasets.md): the CT
# gantry scan scenario (config/scenarios/ct_gantry_scan.yaml: CT bearing, housing sensor,
# spin-up, scan, spin-down, rotating unbalance), one thread, into a bag and into NPY, and
# the run-to-failure scenario (a growing spall) into a bag. The figure is simulated
# seconds per CPU second of the generating thread; "output" is the share of that CPU
# spent converting and writing (bag, NPY, health analysis, ball loads).
# Usage: BEARING_SIM_BUILD=/tmp/build_x bench/bench_generate.sh [duration_s of run-to-failure, default 60]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BEARING_SIM_BUILD:-$root/build}"
tool="$build/devel/lib/bearing_sim/bearing_tool"
out="$(mktemp -d /tmp/bench_generate_XXXXXX)"
trap 'rm -rf "$out"' EXIT
rtf_duration="${1:-60}"
run() {
  local label="$1"; shift
  local line
  line="$("$tool" generate "$@" --out "$out" --threads 1 --quiet | grep '^total:')"
  printf '%-44s %s\n' "$label" "${line#total: }"
}
run "ct_gantry_scan (35 s), bag" "$root/config/scenarios/ct_gantry_scan.yaml" --format bag
run "ct_gantry_scan (35 s), npy" "$root/config/scenarios/ct_gantry_scan.yaml" --format npy
run "ct_gantry_run_to_failure (${rtf_duration} s), bag" "$root/config/scenarios/ct_gantry_run_to_failure.yaml" \
  --format bag --duration-s "$rtf_duration"
