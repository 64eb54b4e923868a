#!/usr/bin/env bash
# The whole extremes sweep (tests/cli/test_extremes.cpp; the test suite runs a sample):
# every value option of every command and every number of a scene file and an atmosphere
# file at 0, -0, 1e-300, 1e308, -1e308, NaN, +-inf and the empty string, each number
# inside a value in turn. Prints the failures, then the tally and the time.
# Usage: bench/extremes_sweep.sh [gtest filter, default Extremes.*]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
build_dir=${UMBRA_BUILD_DIR:-build}
start=$(date +%s)
status=0
UMBRA_EXTREMES=full xvfb-run -a "$build_dir/tests/cli/test_extremes" --gtest_filter="${1:-Extremes.*}" \
  --gtest_brief=1 || status=$?
echo "$(( $(date +%s) - start )) s"
exit $status
