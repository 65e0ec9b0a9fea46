#!/usr/bin/env bash
# Builds bearing_tool, the core tests and the tool tests with AddressSanitizer and
# UndefinedBehaviorSanitizer (-DBEARING_SIM_SANITIZE=ON) in a build directory of their own
# ($BEARING_SIM_SANITIZE_BUILD, default build-asan/) and runs them. Ends with
# "N passed, N failed" (test executables); exit 0 only if every one passed with no report.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
source "$here/../scripts/env.sh"
build="${BEARING_SIM_SANITIZE_BUILD:-$BEARING_SIM_ROOT/build-asan}"
mkdir -p "$build"
start=$(date +%s)
cmake -S "$BEARING_SIM_ROOT" -B "$build" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCATKIN_ENABLE_TESTING=ON -DBEARING_SIM_SANITIZE=ON > "$build/configure.log" 2>&1 \
  || { cat "$build/configure.log"; exit 1; }
tests=(test_core test_bearing_tool)  # the core's suites and the tool's, one program each
cmake --build "$build" -j "$(nproc)" -- bearing_sim_tool "${tests[@]/#/bearing_sim_}" > "$build/build.log" 2>&1 \
  || { tail -50 "$build/build.log"; exit 1; }
built=$(date +%s)
echo "sanitize_test: built in $((built - start)) s"

set +u  # catkin's setup hooks read unset variables
source "$build/devel/setup.bash"
set -u
# Leaks, memory errors and undefined behaviour all end the program with a non-zero status.
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:exitcode=86"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=87"  # not 1: a run that fails on purpose exits 1
passed=0
failed=0
mkdir -p "$build/sanitize_logs"
for t in "${tests[@]}"; do
  exe="$build/devel/lib/bearing_sim/bearing_sim_$t"
  log="$build/sanitize_logs/$t.log"
  if (cd "$BEARING_SIM_ROOT" && "$exe") > "$log" 2>&1 \
      && ! grep -qE "runtime error:|ERROR: (Address|Leak)Sanitizer" "$log"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAILED $t (log: $log)"
    grep -E "runtime error:|ERROR: (Address|Leak)Sanitizer|SUMMARY|\[  FAILED  \]" "$log" | head -20
  fi
done
echo "sanitize_test: tests ran in $(( $(date +%s) - built )) s"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
