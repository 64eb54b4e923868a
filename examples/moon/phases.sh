#!/usr/bin/env bash
# The Moon's phases over a month (October-November 2026), one frame per lunar day (24 h
# 50.5 min) from the new Moon of 2026-10-10, seen from the equator at 60 W when it crosses
# the meridian (examples/scenes/moon-phases-2026.json): the Hapke–Lommel–Seeliger Moon with
# the Clementine albedo map (marble-qt-data), libration and earthshine, at the full Moon's
# exposure. Writes OUT_DIR/phase-00.png .. phase-28.png and OUT_DIR/moon.csv (the Moon's
# numbers at each frame: phase angle, illuminated fraction, V, libration, ...).
# Usage: examples/moon/phases.sh [OUT_DIR] [SIZE]      (default moon-out, 360)
#   Needs an X display: run under xvfb-run -a on a headless machine (or no DISPLAY: EGL).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ -z "${UMBRA:-}" ]; then
  if command -v umbra >/dev/null; then UMBRA=umbra; else UMBRA="$here/../../build/app/cli/umbra"; fi
fi
out="${1:-moon-out}"
size="${2:-360}"
mkdir -p "$out"
from=2026-10-10T16:00:00Z to=2026-11-09T04:00:00Z step=1490.5min
"$UMBRA" render "$here/../scenes/moon-phases-2026.json" --from "$from" --to "$to" --step "$step" \
  --size "${size}x${size}" -o "$out/phase-%02d.png"
"$UMBRA" moon --from "$from" --to "$to" --step "$step" --observer 0,-60 --csv "$out/moon.csv" >/dev/null
echo "wrote $out/phase-00.png .. and $out/moon.csv"
