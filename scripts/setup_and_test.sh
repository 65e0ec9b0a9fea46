#!/usr/bin/env bash
# Install what is missing, build, run every test (gtest, rostest, the install and lint test),
# and end with a line "N passed, N failed, N skipped". Exit status 0 only if every test passed.
# Each phase's wall and CPU time goes to stderr. BEARING_SIM_TEST_JOBS (default 2) test
# programs run at a time: most of them wait on a real-time node, and each rostest has a ROS
# master on a port of its own; make's --output-sync keeps each program's output in one piece.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
TIMEFORMAT='install: %0R s wall, %0U s user, %0S s sys'
time "$here/../dev/install_deps.sh" || exit 1
# The libraries, programs and tests, configured once.
TIMEFORMAT='build: %0R s wall, %0U s user, %0S s sys'
time "$here/../dev/build.sh" all tests || exit 1
source "$here/env.sh"
set +u  # catkin's setup hooks read unset variables
source "$BEARING_SIM_BUILD/devel/setup.bash"
set -u
rm -rf "$BEARING_SIM_BUILD/test_results"
TIMEFORMAT='tests: %0R s wall, %0U s user, %0S s sys'
# A test program that never ends must not hold the run up: after BEARING_SIM_TEST_TIMEOUT_S
# (default 2400 s, ten times a loaded run) the test programs are stopped, and the suites that
# wrote no results count as failed below. grep passes each line on at once, so a log cut
# short shows how far the run got.
time timeout --kill-after=30 "${BEARING_SIM_TEST_TIMEOUT_S:-2400}" \
  cmake --build "$BEARING_SIM_BUILD" -- -j"${BEARING_SIM_TEST_JOBS:-2}" --output-sync=target run_tests 2>&1 \
  | tee "$BEARING_SIM_BUILD/run_tests.log" \
  | grep --line-buffered -E '^\[ *(RUN|OK|FAILED|PASSED) |^\[ROSTEST\]|^(SUMMARY|  \* RESULT|FAILURE)|Failure|Error|\.\.\. (ok|FAIL|ERROR|skipped)|SKIPPED' || true
# Built without LCM (-DBEARING_SIM_WITH_LCM=OFF): its suites are not expected, and said so.
without=()
grep -q '^BEARING_SIM_WITH_LCM:BOOL=OFF' "$BEARING_SIM_BUILD/CMakeCache.txt" && without+=(--without lcm)
/usr/bin/python3 "$here/../dev/count_test_results.py" "$BEARING_SIM_BUILD/test_results" "$here/../test/expected_suites.txt" \
  "${without[@]}"
