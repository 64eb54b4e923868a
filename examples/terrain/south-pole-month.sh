#!/usr/bin/env bash
# Lighting of a (synthetic) landing site at the lunar south pole over a synodic month:
# one shadow map (visible fraction of the solar disc, 16-bit linear PNG, north up) every
# 3.69 days, the Sun from the ephemeris. The Sun stays within ~1.6 deg of the horizon and
# goes once around it; rims cast shadows tens of kilometres long. Then the month's
# lighting statistics every hour (maps in site-lighting.exr; the centre and two points on
# rims in site-points.csv, with the Earth's visibility).
#
#   examples/terrain/south-pole-month.sh [OUT_DIR] [SIZE]     (defaults: out/terrain, 1024)
#
# With a real DEM (GeoTIFF in a polar stereographic CRS, metres), replace
# "--synthetic 7 --size $size" by "--dem FILE.tif".
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/terrain}
size=${2:-1024}
umbra=${UMBRA_BUILD_DIR:-build}/app/cli/umbra
mkdir -p "$out"
start=$(date -u -d "2024-01-11T11:57:00Z" +%s)  # a new Moon
for k in 0 1 2 3 4 5 6 7; do
  t=$(date -u -d "@$((start + k * 318900))" +%Y-%m-%dT%H:%M:%SZ)  # 29.53 days / 8
  "$umbra" terrain shadow --synthetic 7 --size "$size" --time "$t" --output "$out/south-pole-$k.png"
done
"$umbra" terrain lighting --synthetic 7 --size "$size" --from 2024-01-11T11:57:00Z --to 2024-02-10T00:00:00Z \
  --step 1h --point $((size / 2)),$((size / 2)) --point $((size / 5)),$((size * 4 / 5)) --point $((size * 4 / 5)),$((size / 4)) \
  --csv "$out/site-points.csv" --output "$out/site-lighting.exr"
