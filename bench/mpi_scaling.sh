#!/usr/bin/env bash
# How umbra's work spreads over MPI ranks on this machine, and what that projects to many
# ranks. Three jobs, each run whole (mpirun -n R umbra ...), RUNS times per rank count,
# every rank with THREADS threads (OpenMP's, and llvmpipe's for the frames):
#   eclipse  the Earth eclipse LuTs, `umbra precompute eclipse --occluder earth
#            --atmosphere earth` at default sizes, the Bruneton tables read from a cache made
#            once beforehand (the LuTs' texels are what the ranks share);
#   frames   `umbra render` of the 2015-09-28 lunar eclipse, FRAMES frames at 640x360;
#   sweep    `umbra sweep examples/sweeps/moon-in-totality-vs-stratospheric-aerosols.json
#            --no-cache` with its first 4 cases (as many per rank), each with its own
#            atmosphere tables.
# For each: the median wall time at 1 and 2 ranks; the serial part S (the same command with
# next to no parallel work: LuTs of 8x8 and 2x2x2 texels; for the frames and the sweep, one
# frame and one case, less the time of a frame or a case, T(1) from the two), the
# parallel part P = T(1) - S, the most time a rank spent in collectives C (communication
# and waiting for the other rank, as the command reports it), and the speed-up projected to 64 ranks by
# Amdahl's law with C growing as log2 of the ranks: T(64) = S + P / 64 + C(2) log2(64)
# (for the sweep: a sweep of 64 cases or more). Markdown out.
#
#   bench/mpi_scaling.sh [--runs N] [--threads T] [--frames F] [--jobs "eclipse frames sweep"]
#       [--umbra build/app/cli/umbra] [--work DIR]
#
# Needs mpirun (openmpi-bin) and, for the frames, a display (without DISPLAY the script
# runs itself under xvfb-run).
set -euo pipefail

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
[[ ${1:-} == -h || ${1:-} == --help ]] && { usage; exit 0; }
here=$(cd "$(dirname "$0")/.." && pwd)
runs=3 threads=1 frames=24 jobs="eclipse frames sweep" umbra="$here/build/app/cli/umbra" work="${TMPDIR:-/tmp}/umbra-mpi-bench"
while [[ $# -gt 0 ]]; do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --umbra) umbra=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    *) echo "mpi_scaling: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
for v in "$runs" "$threads" "$frames"; do
  [[ $v =~ ^[1-9][0-9]*$ ]] || { echo "mpi_scaling: expected a positive integer, got $v" >&2; exit 2; }
done
[[ -x $umbra ]] || { echo "mpi_scaling: $umbra: not built" >&2; exit 2; }
command -v mpirun >/dev/null || { echo "mpi_scaling: no mpirun (apt-get install openmpi-bin)" >&2; exit 2; }
if [[ -z ${DISPLAY:-} && -z ${UMBRA_MPI_BENCH_XVFB:-} ]]; then
  UMBRA_MPI_BENCH_XVFB=1 exec xvfb-run -a "$0" --runs "$runs" --threads "$threads" --frames "$frames" --jobs "$jobs" \
    --umbra "$umbra" --work "$work"
fi

mkdir -p "$work"
cores=$(nproc --all)
# Every rank THREADS threads: OpenMP's, and llvmpipe's for the frames (it would take every core).
export UMBRA_CACHE_DIR="$work/cache" OMP_NUM_THREADS=$threads LP_NUM_THREADS=$threads
mpi=(mpirun --oversubscribe --allow-run-as-root --bind-to none)
scene="$here/examples/scenes/lunar-eclipse-2015-09-28.json"

eclipse() {  # ranks, then extra options
  local n=$1; shift
  rm -f "$work"/cache/eclipse-*.exr
  "${mpi[@]}" -n "$n" "$umbra" precompute eclipse --occluder earth --atmosphere earth --output "$work/out" "$@"
}
frames() {  # ranks, last frame's time
  local n=$1
  rm -rf "$work/frames" && mkdir -p "$work/frames"
  "${mpi[@]}" -n "$n" "$umbra" render "$scene" --size 640x360 --from 2015-09-28T00:00:00Z --to "$2" --step 10min \
    --output "$work/frames/f-%03d.png"
}
last=$(date -u -d "2015-09-28T00:00:00Z + $(( (frames - 1) * 10 )) minutes" +%Y-%m-%dT%H:%M:%SZ)

# Times a job `runs` times; prints "median_wall median_collectives" (collectives: rank 0's,
# from the command's last line; 0 on one rank).
timed() {
  local walls=() colls=() out t0 t1
  for ((i = 0; i < runs; ++i)); do
    t0=$(date +%s.%N)
    out=$("$@" 2>/dev/null)
    t1=$(date +%s.%N)
    walls+=("$(awk -v a="$t1" -v b="$t0" 'BEGIN { print a - b }')")
    colls+=("$(grep -o 'at most [0-9.]* s' <<<"$out" | grep -o '[0-9.][0-9.]*' | head -1 || true)")
  done
  median() { printf '%s\n' "$@" | sed 's/^$/0/' | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
  echo "$(median "${walls[@]}") $(median "${colls[@]}")"
}

eclipse 1 >/dev/null 2>&1  # the Bruneton tables and the Lorenz-Mie optics into the cache
"$umbra" render "$scene" --size 64x36 --output "$work/warm.png" >/dev/null 2>&1  # the airless LuT, the stars

report() {  # name, serial, one rank, two ranks
  local name=$1 s=$2 t1 t2 c2
  read -r t1 _ <<<"$3"
  read -r t2 c2 <<<"$4"
  awk -v name="$name" -v s="$s" -v t1="$t1" -v t2="$t2" -v c="$c2" 'BEGIN {
    p = t1 - s; if (p < 0) p = 0
    t64 = s + p / 64 + c * 6
    printf "| %s | %.2f s | %.2f s | %.2fx | %.2f s (%.0f %%) | %.2f s (%.0f %%) | %.2f s (%.1f %%) | %.1fx |\n",
      name, t1, t2, t1 / t2, s, 100 * s / t1, p, 100 * p / t1, c, 100 * c / t2, t1 / t64 }'
}

echo "ranks x $threads thread(s) (OpenMP, llvmpipe), median of $runs runs; $cores cores"
echo
echo "| job | 1 rank | 2 ranks | speed-up | serial S | parallel P | collectives C (of 2-rank wall) | projected 64 ranks |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|"
# The serial part of a job of `units` units: one unit's run less a unit's time.
serialOf() {  # one unit's wall, all units' wall, units
  awk -v one="$1" -v all="$2" -v n="$3" 'BEGIN { s = one - (all - one) / (n - 1); print (s < 0 ? 0 : s) }'
}
sweep() {  # ranks, file
  "${mpi[@]}" -n "$1" "$umbra" sweep "$2" --no-cache --csv "$work/sweep.csv"
}

for job in $jobs; do
  case $job in
    eclipse)
      read -r es _ <<<"$(timed eclipse 1 --size 8 --limb-lut-size 2 --layers 1)"
      report "eclipse LuTs (256x256, 64x64x64)" "$es" "$(timed eclipse 1)" "$(timed eclipse 2)" ;;
    frames)
      read -r f1 _ <<<"$(timed frames 1 2015-09-28T00:00:00Z)"
      fAll=$(timed frames 1 "$last")
      report "$frames frames 640x360" "$(serialOf "$f1" "${fAll%% *}" "$frames")" "$fAll" "$(timed frames 2 "$last")" ;;
    sweep)
      sweepFile="$here/examples/sweeps/moon-in-totality-vs-stratospheric-aerosols.json"
      sed 's/\[1, 3, 10, 30, 100\]/[1]/' "$sweepFile" >"$work/one-case.json"
      sed 's/\[1, 3, 10, 30, 100\]/[1, 3, 10, 30]/' "$sweepFile" >"$work/four-cases.json"
      read -r s1 _ <<<"$(timed sweep 1 "$work/one-case.json")"
      sAll=$(timed sweep 1 "$work/four-cases.json")
      report "sweep, 4 cases" "$(serialOf "$s1" "${sAll%% *}" 4)" "$sAll" "$(timed sweep 2 "$work/four-cases.json")" ;;
    *) echo "mpi_scaling: --jobs: unknown job $job (eclipse, frames, sweep)" >&2; exit 2 ;;
  esac
done
