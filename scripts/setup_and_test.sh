#!/usr/bin/env bash
# Install what is missing, build, run every test (gtest, rostest, the install and lint test),
# and end with a line "N passed, N failed, N skipped". Exit status 0 only if every test passed.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$here/../dev/install_deps.sh" || exit 1
"$here/../dev/build.sh" || exit 1
source "$here/env.sh"
"$here/../dev/build.sh" tests || exit 1
set +u  # catkin's setup hooks read unset variables
source "$BEARING_SIM_BUILD/devel/setup.bash"
set -u
rm -rf "$BEARING_SIM_BUILD/test_results"
cmake --build "$BEARING_SIM_BUILD" -- -j1 run_tests 2>&1 | tee "$BEARING_SIM_BUILD/run_tests.log" \
  | grep -E '^\[ *(RUN|OK|FAILED|PASSED) |^\[ROSTEST\]|^(SUMMARY|  \* RESULT|FAILURE)|Failure|Error|\.\.\. (ok|FAIL|ERROR|skipped)|SKIPPED' || true
# Built without LCM (-DBEARING_SIM_WITH_LCM=OFF): its suites are not expected, and said so.
without=()
grep -q '^BEARING_SIM_WITH_LCM:BOOL=OFF' "$BEARING_SIM_BUILD/CMakeCache.txt" && without+=(--without lcm)
/usr/bin/python3 "$here/../dev/count_test_results.py" "$BEARING_SIM_BUILD/test_results" "$here/../test/expected_suites.txt" \
  "${without[@]}"
