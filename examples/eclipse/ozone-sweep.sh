#!/usr/bin/env bash
# Ozone and the colour of the umbra (eclipse paper, Figure 13): no ozone, and a tent layer at
# 25 km with peak number densities 4e18 and 6e18 1/m^3 (the earth preset has 5.374e18).
# Usage: examples/eclipse/ozone-sweep.sh [OUTPUT_DIR]
source "$(dirname "$0")/common.sh"
for name in earth-no-ozone earth-ozone-4e18 earth-ozone-6e18; do
  "$UMBRA" profile shadow --occluder earth --atmosphere "$here/atmospheres/$name.json" --distance 384400km \
    --csv "$out/shadow-$name.csv" --plot "$out/shadow-$name.svg" "${extra[@]}"
done
echo "umbra centre and rim (offset 0 and about 4200 km), g/r and b/g:"
for name in earth-no-ozone earth-ozone-4e18 earth-ozone-6e18; do
  awk -F, -v n="$name" 'NR == 2 || (NR > 2 && $1 >= 4200 && !rim) {
      if (NR > 2) rim = 1; printf "  %-18s %7.0f km  g/r %.4f  b/g %.4f\n", n, $1, $3 / $2, $4 / $3 }' \
    "$out/shadow-$name.csv"
done
