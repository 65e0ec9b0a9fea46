#!/usr/bin/env bash
# Configures and builds the package into $BEARING_SIM_BUILD (default build/, devel space build/devel).
# Arguments are make targets (default: all); $BEARING_SIM_CMAKE_ARGS adds CMake options, e.g.
# BEARING_SIM_CMAKE_ARGS=-DBEARING_SIM_WITH_LCM=OFF.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/env.sh"
# shellcheck disable=SC2086  # BEARING_SIM_CMAKE_ARGS is a list of options
cmake -S "$BEARING_SIM_ROOT" -B "$BEARING_SIM_BUILD" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
  -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON -DCMAKE_EXPORT_COMPILE_COMMANDS=ON ${BEARING_SIM_CMAKE_ARGS:-} \
  > "$BEARING_SIM_BUILD.configure.log" 2>&1 \
  || { cat "$BEARING_SIM_BUILD.configure.log"; exit 1; }
cmake --build "$BEARING_SIM_BUILD" -j "$(nproc)" -- "$@"
