#!/usr/bin/env bash
# The main job: installs the dependencies, builds umbra, then
#   1. renders the 2015-09-28 lunar eclipse scene offscreen to a PNG,
#   2. writes Earth's eclipse-shadow lookup table as EXR,
#   3. writes the cross-section of Earth's shadow at the Moon's distance in that scene
#      (356 849 km, the eclipse's perigee) as CSV and PNG,
#   4. writes the same cross-section through Earth's atmosphere after the 2015 Calbuco
#      eruption (refracted and scattered light in the umbra, R/G/B, log scale) as CSV and PNG;
#      the atmosphere tables are computed once (about 20 s) and cached.
# Output goes to out/ (or the folder given as the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
out=${1:-out}
mkdir -p "$out"
umbra=${UMBRA_BUILD_DIR:-build}/app/cli/umbra
scene=examples/scenes/lunar-eclipse-2015-09-28.json

echo "== rendering $scene"
xvfb-run -a -s "-screen 0 1280x1024x24" "$umbra" render "$scene" --output "$out/lunar-eclipse-2015-09-28.png"
echo "== Earth's shadow lookup table"
"$umbra" precompute shadow --occluder Earth --output "$out/earth-shadow-lut.exr"
echo "== Earth's shadow at the Moon's distance"
xvfb-run -a -s "-screen 0 1280x1024x24" "$umbra" profile shadow --scene "$scene" --no-atmosphere \
  --csv "$out/earth-shadow-at-moon.csv" --plot "$out/earth-shadow-at-moon.png"
echo "== Earth's shadow at the Moon's distance, through the atmosphere (earth-2015-calbuco)"
xvfb-run -a -s "-screen 0 1280x1024x24" "$umbra" profile shadow --occluder Earth --atmosphere earth-2015-calbuco \
  --distance 356849km --csv "$out/earth-shadow-at-moon-atmosphere.csv" --plot "$out/earth-shadow-at-moon-atmosphere.png"

echo
echo "Files written:"
for f in lunar-eclipse-2015-09-28.png earth-shadow-lut.exr earth-shadow-at-moon.csv earth-shadow-at-moon.png \
  earth-shadow-at-moon-atmosphere.csv earth-shadow-at-moon-atmosphere.png; do
  echo "  $(cd "$out" && pwd)/$f"
done
