#!/usr/bin/env bash
# Installs the dependencies, builds umbra and runs every test (rendering tests run their
# binaries under xvfb-run). Usage: scripts/test.sh [--sanitize] [ctest arguments...]
#   --sanitize: the same suite built with AddressSanitizer and UBSan (-DUMBRA_SANITIZE=ON)
#   into build-sanitize/; any report fails the test that made it.
set -euo pipefail
cd "$(dirname "$0")/.."
configure=()
build_dir=${UMBRA_BUILD_DIR:-build}
if [ "${1:-}" = "--sanitize" ]; then
  shift
  build_dir=${UMBRA_BUILD_DIR:-build-sanitize}
  configure=(-DUMBRA_SANITIZE=ON)
  # Leaks are not errors here: VTK, Qt and Mesa keep allocations until exit by design.
  export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
fi
scripts/install-deps.sh
UMBRA_BUILD_DIR="$build_dir" scripts/build.sh "${configure[@]}"
# Tests must not depend on a cache left by earlier runs.
export UMBRA_CACHE_DIR="$PWD/$build_dir/test-cache"
rm -rf "$UMBRA_CACHE_DIR"
cd "$build_dir"
ctest --output-on-failure -j "${UMBRA_JOBS:-2}" "$@"
