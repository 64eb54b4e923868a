#!/usr/bin/env bash
# The total lunar eclipse of 2015-09-28 at 30-minute steps from 01:00 to 03:30 UTC (eclipse
# paper, Figure 11): the Moon seen from Earth (centre row) and Earth seen from the lunar
# north pole (bottom row), both with the Calbuco atmosphere; Earth's shadow on the Moon
# comes from the atmospheric shadow LuT (only the Moon's columns of it, cached), and Earth's
# ring, under a pixel wide, from the limb-luminance LuT (eclipse paper, 5.4).
# Usage: examples/eclipse/eclipse-2015-series.sh [OUTPUT_DIR]
#   UMBRA_EXAMPLE_FLAGS="--atmosphere-tables small --size 160x120" for a quick look; the
#   default tables are precomputed once (a few minutes on 2 cores), then cached.
#   Needs an X display: run under xvfb-run -a on a headless machine.
source "$(dirname "$0")/common.sh"
scenes="$here/../scenes"
# The Moon's exposures follow the photographs of Figure 11 (0, +4, +9, +13, +13, +9 EV
# relative to the first).
exposures=(-7 -3 2 6 6 2)
k=0
for time in 01:00 01:30 02:00 02:30 03:00 03:30; do
  stamp="${time/:/}"
  "$UMBRA" render "$scenes/lunar-eclipse-2015-09-28-moon.json" --time "2015-09-28T${time}:00Z" \
    --exposure "${exposures[$k]}" -o "$out/moon-$stamp.png" "${extra[@]}"
  k=$((k + 1))
  "$UMBRA" render "$scenes/earth-from-lunar-north-pole-2015-09-28.json" --time "2015-09-28T${time}:00Z" --refraction \
    -o "$out/earth-$stamp.png" "${extra[@]}"
done
