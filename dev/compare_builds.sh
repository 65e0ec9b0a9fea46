#!/usr/bin/env bash
# The speed of this tree's core library against another commit's, timed in turns within one
# process (bench/paired): on a shared machine whose speed drifts by tens of percent within
# minutes, bench_simulate cannot show a change of a few percent; neighbouring turns of the
# two builds see the same machine, and the median of their ratios resolves 1-2 %.
# Usage: dev/compare_builds.sh BASE_COMMIT [SIMD_TARGET=AVX2] [TURNS=61]
# BASE_COMMIT's sources are unpacked (git archive) and built in $BEARING_SIM_COMPARE_DIR
# (default /tmp/bearing_sim_compare); this tree's core library is built by dev/build.sh.
# Both builds run the cases of this tree's config files. Times are CPU time of one core.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/env.sh"
if [ $# -lt 1 ]; then
  sed -n '2,10p' "$0"
  exit 2
fi
target=${2:-AVX2}
turns=${3:-61}
work=${BEARING_SIM_COMPARE_DIR:-/tmp/bearing_sim_compare}
rev=$(git -C "$BEARING_SIM_ROOT" rev-parse --short "$1")
tree="$work/tree_$rev"
if [ ! -d "$tree" ]; then
  mkdir -p "$tree"
  git -C "$BEARING_SIM_ROOT" archive "$rev" | tar -x -C "$tree"
fi
echo "building $rev's core library in $work/build_$rev and this tree's in $BEARING_SIM_BUILD" >&2
base_build="$tree/dev/build.sh"  # scripts/build.sh in commits before dev/
[ -x "$base_build" ] || base_build="$tree/scripts/build.sh"
BEARING_SIM_BUILD="$work/build_$rev" "$base_build" bearing_sim_core > "$work/build_$rev.log" 2>&1 \
  || { tail -20 "$work/build_$rev.log"; exit 1; }
"$BEARING_SIM_ROOT/dev/build.sh" bearing_sim_core > "$work/build_new.log" 2>&1 \
  || { tail -20 "$work/build_new.log"; exit 1; }
driver() {  # source tree, build dir, output
  g++ -O2 -std=c++17 -fPIC -shared -I"$1/include" -I"$1/test/core" -I/usr/include/eigen3 \
    "$BEARING_SIM_ROOT/bench/paired/paired_driver.cpp" -o "$3" \
    -L"$2/devel/lib" -lbearing_sim_core -lyaml-cpp -Wl,-rpath,"$2/devel/lib"
}
driver "$tree" "$work/build_$rev" "$work/driver_$rev.so"
driver "$BEARING_SIM_ROOT" "$BEARING_SIM_BUILD" "$work/driver_new.so"
g++ -O2 "$BEARING_SIM_ROOT/bench/paired/paired_compare.cpp" -o "$work/paired_compare" -ldl
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-); base $rev, new: this tree" >&2
# The core library's thread_local caches use the initial-exec TLS model: a copy loaded into
# a new link namespace needs the static TLS space this reserves.
GLIBC_TUNABLES=glibc.rtld.optional_static_tls=1048576 \
  "$work/paired_compare" "$work/driver_$rev.so" "$work/driver_new.so" "$BEARING_SIM_ROOT" "$target" "$turns"
