#!/usr/bin/env bash
# Installs the dependencies, builds umbra and runs every test (rendering tests run their
# binaries under xvfb-run). Usage: scripts/test.sh [ctest arguments...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build_dir=${UMBRA_BUILD_DIR:-build}
# Tests must not depend on a cache left by earlier runs.
export UMBRA_CACHE_DIR="$PWD/$build_dir/test-cache"
rm -rf "$UMBRA_CACHE_DIR"
cd "$build_dir"
ctest --output-on-failure -j "${UMBRA_JOBS:-2}" "$@"
