#!/usr/bin/env bash
# umbra's spectral sky against the CPU reference of Bruneton's precomputed_atmospheric_scattering
# (atmosphere/reference: double precision, 47 wavelengths 360-820 nm, 4 orders): builds a small
# driver of the reference's Model (bench/peer/bruneton_reference_driver.cc) against a checkout
# of the peer, which precomputes its textures (about 20 minutes on 2 cores; kept in --work, so
# that a second run only reads them) and writes its sky radiance per unit solar irradiance at
# 672 view and Sun geometries; then umbra-bench-peer-reference precomputes umbra's tables of
# the same atmosphere (bench/peer/bruneton-reference.json) at the same wavelengths and prints
# the relative error at every geometry and wavelength, as Markdown.
#
#   bench/peer_reference_accuracy.sh PEER_CHECKOUT [--work DIR] [--bench build/bench/umbra-bench-peer-reference]
#
# PEER_CHECKOUT: a checkout of github.com/ebruneton/precomputed_atmospheric_scattering with its
# submodules (git clone --recursive: external/dimensional_types and external/progress_bar),
# measured at d9954923; it is only read. Needs g++ with C++11 and threads.
set -euo pipefail

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
[[ $# -ge 1 && $1 != -h && $1 != --help ]] || { usage; [[ $# -ge 1 ]] && exit 0; exit 2; }
here=$(cd "$(dirname "$0")/.." && pwd)
peer=$(cd "$1" 2>/dev/null && pwd) || { echo "peer_reference_accuracy: $1: no such directory" >&2; exit 2; }
shift
work="${TMPDIR:-/tmp}/umbra-peer-reference" bench="$here/build/bench/umbra-bench-peer-reference"
while [[ $# -gt 0 ]]; do
  case $1 in
    --work) work=$2; shift 2 ;;
    --bench) bench=$2; shift 2 ;;
    *) echo "peer_reference_accuracy: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
[[ -x $bench ]] || { echo "peer_reference_accuracy: $bench: not built (scripts/build.sh)" >&2; exit 2; }
for f in atmosphere/reference/model.cc atmosphere/reference/functions.cc external/dimensional_types/math/scalar.h \
         external/progress_bar/util/progress_bar.cc; do
  [[ -f $peer/$f ]] || { echo "peer_reference_accuracy: $peer: no $f (a checkout of precomputed_atmospheric_scattering with its submodules?)" >&2; exit 2; }
done

mkdir -p "$work/textures"
driver=$work/bruneton_reference_driver
if [[ ! -x $driver || $here/bench/peer/bruneton_reference_driver.cc -nt $driver ]]; then
  echo "building the reference's driver in $work ..." >&2
  g++ -std=c++11 -O3 -DNDEBUG -pthread -I"$peer" -I"$peer/external" -I"$peer/external/dimensional_types" \
    -I"$peer/external/progress_bar" "$here/bench/peer/bruneton_reference_driver.cc" "$peer/atmosphere/reference/model.cc" \
    "$peer/atmosphere/reference/functions.cc" "$peer/external/progress_bar/util/progress_bar.cc" -o "$driver.tmp"
  mv "$driver.tmp" "$driver"
fi
csv=$work/reference.csv
if [[ ! -s $csv || $driver -nt $csv ]]; then
  echo "the reference's precomputation (textures kept in $work/textures) ..." >&2
  /usr/bin/time -f "reference: %e s wall, %U+%S s cpu, %M KiB peak" "$driver" "$work/textures/" "$csv.tmp" >&2
  mv "$csv.tmp" "$csv"
fi
"$bench" --reference "$csv"
