#!/usr/bin/env bash
# Fuzzes umbra's parsers: scene files, atmosphere files, EXR tables and shadow LuTs, and
# the command line's options (tests/fuzz/). Installs clang and libFuzzer when missing,
# builds the targets with clang, libFuzzer, AddressSanitizer and UBSan into build-fuzz/
# (every library instrumented), and runs each from its seed corpus (tests/fuzz/corpus/).
#
# Usage: scripts/fuzz.sh [--runs N | --seconds S] [TARGET ...]
#   TARGET: scene, atmosphere, exr, cli (default: all four); --runs N executions each
#   (default 1000000), or --seconds S of each. A finding (crash, sanitizer report, timeout
#   of 10 s, an exception other than the parser's own) stops that target, leaves the input
#   in build-fuzz/findings/ and makes the script exit 1; the summary line per target gives
#   the executions, coverage and speed.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=1000000 seconds=""
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    scene|atmosphere|exr|cli) targets+=("$1"); shift ;;
    *) echo "fuzz.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=(scene atmosphere exr cli)

scripts/install-deps.sh
missing=()
for p in clang libclang-rt-14-dev libomp-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

build=${UMBRA_FUZZ_BUILD_DIR:-build-fuzz}
flags="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUMBRA_FUZZ=ON \
  -DUMBRA_BUILD_GUI=OFF -DUMBRA_BUILD_TESTS=OFF -DUMBRA_BUILD_BENCH=OFF \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" >/dev/null
cmake --build "$build" -j "${UMBRA_JOBS:-2}" --target $(printf 'fuzz_%s ' "${targets[@]}")

mkdir -p "$build/findings"
status=0
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
for t in "${targets[@]}"; do
  work="$build/corpus/$t"
  mkdir -p "$work"
  limit=(-runs="$runs")
  [ -z "$seconds" ] || limit=(-max_total_time="$seconds")
  echo "== fuzz_$t (${limit[*]})"
  if ! "$build/tests/fuzz/fuzz_$t" "${limit[@]}" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
      -artifact_prefix="$build/findings/$t-" "$work" "tests/fuzz/corpus/$t" 2> "$build/findings/$t.log"; then
    status=1
    echo "   FINDING: see $build/findings/$t.log"
  fi
  grep -E "^(#[0-9]+\s+DONE|stat::number_of_executed_units|stat::average_exec_per_sec)" "$build/findings/$t.log" | sed 's/^/   /'
done
exit $status
