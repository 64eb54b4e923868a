#!/usr/bin/env bash
# Configures and builds umbra with Ninja into build/ (or $UMBRA_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${UMBRA_BUILD_DIR:-build}
jobs=${UMBRA_JOBS:-2}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$build_dir" -j "$jobs"
