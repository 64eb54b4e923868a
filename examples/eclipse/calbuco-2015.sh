#!/usr/bin/env bash
# The lunar eclipse of 2015-09-28 (eclipse paper, 6.1, Figures 11-12): Earth's shadow at the
# Moon's mean distance with the clear atmosphere and with Calbuco's stratospheric sulphate
# (three times the background), as CSV and Figure 12 style plots (log I/I_sun, R G B).
# Usage: examples/eclipse/calbuco-2015.sh [OUTPUT_DIR]   (plots as SVG; PNG needs xvfb-run -a)
source "$(dirname "$0")/common.sh"
for atmosphere in earth earth-2015-calbuco; do
  "$UMBRA" profile shadow --occluder earth --atmosphere "$atmosphere" --distance 384400km \
    --csv "$out/shadow-$atmosphere.csv" --plot "$out/shadow-$atmosphere.svg" "${extra[@]}"
done
echo "umbra centre (offset 0), I/I_sun r g b:"
for atmosphere in earth earth-2015-calbuco; do
  printf '  %-20s %s\n' "$atmosphere" "$(sed -n 2p "$out/shadow-$atmosphere.csv" | cut -d, -f2-4)"
done
