#!/usr/bin/env bash
# Configures and builds the package into $BEARING_SIM_BUILD (default build/, devel space build/devel).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
cmake -S "$BEARING_SIM_ROOT" -B "$BEARING_SIM_BUILD" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
  -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON > "$BEARING_SIM_BUILD.configure.log" 2>&1 \
  || { cat "$BEARING_SIM_BUILD.configure.log"; exit 1; }
cmake --build "$BEARING_SIM_BUILD" -j "$(nproc)" -- "$@"
