#!/usr/bin/env bash
# umbra's atmosphere tables against Bruneton's precomputed_atmospheric_scattering, side by
# side on this machine: the peer's Model::Init (OpenGL: the GPU, or Mesa's llvmpipe on a
# machine without one) against `umbra atmosphere precompute --preset earth-bruneton --no-cache`
# (the same Earth, table sizes and orders; the command also writes its EXR files), whole
# processes, alternating, RUNS of each. Prints per wavelength count the min and median wall
# time, CPU time (user + system; the peer's includes llvmpipe's threads) and peak RSS of
# each, and the ratios peer / umbra, as Markdown.
#
#   bench/peer_side_by_side.sh PEER_CHECKOUT [--runs N] [--wavelengths "3 15"]
#       [--memory MIB] [--umbra build/app/cli/umbra] [--work DIR]
#
# --memory MIB: umbra runs with `--memory MIB` (the working set it computes the wavelengths
# in, a batch at a time; default: its own default).
#
# PEER_CHECKOUT: a checkout of github.com/ebruneton/precomputed_atmospheric_scattering
# (measured at d9954923); it is only read. The driver (bench/peer/bruneton_init_driver.cc)
# is built against it in --work (default: $TMPDIR/umbra-peer-bench), never in umbra's tree;
# it needs g++, freeglut and OpenGL 3.3 (libglut-dev, libgl-dev), and a display: without
# DISPLAY the script runs itself under xvfb-run.
set -euo pipefail

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
[[ $# -ge 1 && $1 != -h && $1 != --help ]] || { usage; [[ $# -ge 1 ]] && exit 0; exit 2; }
here=$(cd "$(dirname "$0")/.." && pwd)
peer=$(cd "$1" 2>/dev/null && pwd) || { echo "peer_side_by_side: $1: no such directory" >&2; exit 2; }
shift
runs=3 wavelengths="3 15" memory="" umbra="$here/build/app/cli/umbra" work="${TMPDIR:-/tmp}/umbra-peer-bench"
while [[ $# -gt 0 ]]; do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --wavelengths) wavelengths=$2; shift 2 ;;
    --memory) memory=$2; shift 2 ;;
    --umbra) umbra=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    *) echo "peer_side_by_side: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "peer_side_by_side: --runs: expected a positive integer, got $runs" >&2; exit 2; }
[[ -z $memory || $memory =~ ^[1-9][0-9]*$ ]] || { echo "peer_side_by_side: --memory: expected a positive integer (MiB), got $memory" >&2; exit 2; }
umbraOptions=(${memory:+--memory "$memory"})
for w in $wavelengths; do
  [[ $w == 3 || $w == 15 ]] || { echo "peer_side_by_side: --wavelengths: 3 and/or 15 (the peer's modes), got $w" >&2; exit 2; }
done
[[ -x $umbra ]] || { echo "peer_side_by_side: $umbra: not built (scripts/build.sh)" >&2; exit 2; }
for f in atmosphere/model.cc atmosphere/model.h atmosphere/definitions.glsl atmosphere/functions.glsl \
         external/glad/src/glad.cc; do
  [[ -f $peer/$f ]] || { echo "peer_side_by_side: $peer: no $f (not a checkout of precomputed_atmospheric_scattering?)" >&2; exit 2; }
done

if [[ -z ${DISPLAY:-} && -z ${UMBRA_PEER_BENCH_INNER:-} ]]; then
  exec env UMBRA_PEER_BENCH_INNER=1 xvfb-run -a -s "-screen 0 640x480x24" "$0" "$peer" --runs "$runs" \
    --wavelengths "$wavelengths" ${memory:+--memory "$memory"} --umbra "$umbra" --work "$work"
fi

# ---- the driver --------------------------------------------------------------------------
mkdir -p "$work/gen/atmosphere" "$work/obj"
for g in definitions functions; do  # the GLSL as C++ strings, as the peer's own build makes them
  { printf 'const char %s_glsl[] = R"***(\n' "$g"; cat "$peer/atmosphere/$g.glsl"; printf ')***";\n'; } \
    > "$work/gen/atmosphere/$g.glsl.inc"
done
flags=(-std=c++11 -O3 -DNDEBUG -I"$work/gen" -I"$peer" -I"$peer/external/glad/include")
driver=$work/bruneton_init_driver
if [[ ! -x $driver || $here/bench/peer/bruneton_init_driver.cc -nt $driver ]]; then
  echo "building the peer's driver in $work ..." >&2
  g++ "${flags[@]}" -c "$peer/atmosphere/model.cc" -o "$work/obj/model.o"
  g++ "${flags[@]}" -c "$peer/external/glad/src/glad.cc" -o "$work/obj/glad.o"
  g++ "${flags[@]}" -c "$here/bench/peer/bruneton_init_driver.cc" -o "$work/obj/driver.o"
  g++ "$work"/obj/*.o -pthread -ldl -lglut -lGL -o "$driver"
fi

# ---- the runs ----------------------------------------------------------------------------
# One run: wall, CPU (user + system) seconds and peak RSS (KiB) of the whole process.
measure() {  # measure OUT_FILE COMMAND...
  local out=$1; shift
  /usr/bin/time -f '%e %U %S %M' -o "$out.time" "$@" > "$out.log" 2>&1 || {
    echo "peer_side_by_side: failed: $* (log: $out.log)" >&2; exit 1; }
  awk '{ printf "%s %.2f %s\n", $1, $2 + $3, $4 }' "$out.time"
}
stat() {  # stat COLUMN FILE: "min median" of a column
  sort -g -k"$1","$1" "$2" | awk -v c="$1" '{ v[NR] = $c } END {
    m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "%s %s", v[1], m }'
}
echo "| wavelengths | runs | peer wall min / median [s] | umbra wall min / median [s] | wall ratio (medians) | peer CPU [s] | umbra CPU [s] | peer peak RSS [MiB] | umbra peak RSS [MiB] |"
echo "|---|---|---|---|---|---|---|---|---|"
for w in $wavelengths; do
  : > "$work/peer-$w.runs"; : > "$work/umbra-$w.runs"
  for ((i = 1; i <= runs; ++i)); do
    echo "  $w wavelengths, run $i of $runs: the peer ..." >&2
    measure "$work/peer-$w-$i" "$driver" "$w" >> "$work/peer-$w.runs"
    echo "  $w wavelengths, run $i of $runs: umbra ..." >&2
    rm -rf "$work/umbra-out"
    measure "$work/umbra-$w-$i" "$umbra" atmosphere precompute --preset earth-bruneton --wavelengths "$w" \
      --no-cache "${umbraOptions[@]}" --output "$work/umbra-out" >> "$work/umbra-$w.runs"
  done
  read -r pw_min pw_med <<< "$(stat 1 "$work/peer-$w.runs")"
  read -r uw_min uw_med <<< "$(stat 1 "$work/umbra-$w.runs")"
  read -r _ pc_med <<< "$(stat 2 "$work/peer-$w.runs")"
  read -r _ uc_med <<< "$(stat 2 "$work/umbra-$w.runs")"
  read -r _ pm_med <<< "$(stat 3 "$work/peer-$w.runs")"
  read -r _ um_med <<< "$(stat 3 "$work/umbra-$w.runs")"
  awk -v w="$w${memory:+ (umbra --memory $memory)}" -v n="$runs" -v a="$pw_min" -v b="$pw_med" -v c="$uw_min" -v d="$uw_med" -v e="$pc_med" \
      -v f="$uc_med" -v g="$pm_med" -v h="$um_med" 'BEGIN {
    printf "| %s | %s | %.1f / %.1f | %.2f / %.2f | %.1fx | %.1f | %.1f | %.0f | %.0f |\n",
      w, n " each, alternating", a, b, c, d, b / d, e, f, g / 1024, h / 1024 }'
done
echo
echo "(peer: $(cd "$peer" && git rev-parse --short HEAD 2>/dev/null || echo "not a git checkout"); $(glxinfo -B 2>/dev/null | sed -n 's/^OpenGL renderer string: //p' | head -1))"
