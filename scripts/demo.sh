#!/usr/bin/env bash
# The main job: installs the dependencies, builds umbra, then
#   1. renders the Moon at the totality of the 2015-09-28 lunar eclipse, lit through Earth's
#      atmosphere after the Calbuco eruption (the copper Moon, with its maria: the
#      Clementine albedo map of marble-qt-data on the Hapke–Lommel–Seeliger Moon),
#   2. renders the same eclipse at its partial phase (the umbra dark red, the rest sunlit),
#   3. writes Earth's eclipse-shadow lookup table as EXR,
#   4. writes the cross-section of Earth's shadow at the Moon's distance in that scene
#      (356 849 km, the eclipse's perigee) as CSV and PNG,
#   5. writes the same cross-section through Earth's atmosphere after the 2015 Calbuco
#      eruption (refracted and scattered light in the umbra, R/G/B, log scale) as CSV and PNG,
#   6. renders the sky around the Moon in a 40 degree field at the partial phase and at
#      totality: the moonlit air hides the fainter stars, then the stars of kstars-data's
#      catalogue come out as the Moon's light goes,
#   7. renders the totality of the solar eclipse of 2027-08-02 from Luxor, Egypt: the sky of
#      the Moon's umbra (dark overhead, the horizon orange all round), the corona round the
#      Moon, Venus, Mercury and Jupiter, the ground lit by that sky; and plots that sky's radiance along the vertical
#      through the Sun and the almucantar (the quadrature, CSV and PNG).
#   The atmosphere tables and the atmospheric shadow LuT are computed once (about a minute
#   on 2 cores) and cached.
# Output goes to out/ (or the folder given as the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
out=${1:-out}
mkdir -p "$out"
umbra=${UMBRA_BUILD_DIR:-build}/app/cli/umbra
scene=examples/scenes/lunar-eclipse-2015-09-28.json
moon=examples/scenes/lunar-eclipse-2015-09-28-moon.json
xvfb=(xvfb-run -a -s "-screen 0 1280x1024x24")

echo "== the Moon at totality, 2015-09-28T02:47Z, through Earth's atmosphere"
"${xvfb[@]}" "$umbra" render "$moon" --time 2015-09-28T02:47:00Z --size 960x720 \
  --output "$out/lunar-eclipse-2015-09-28-totality.png"
echo "== the partial phase, 01:45Z"
"${xvfb[@]}" "$umbra" render "$moon" --time 2015-09-28T01:45:00Z --exposure -4 --size 960x720 \
  --output "$out/lunar-eclipse-2015-09-28-partial.png"
echo "== Earth's shadow lookup table"
"$umbra" precompute shadow --occluder Earth --output "$out/earth-shadow-lut.exr"
echo "== Earth's shadow at the Moon's distance"
"${xvfb[@]}" "$umbra" profile shadow --scene "$scene" --no-atmosphere \
  --csv "$out/earth-shadow-at-moon.csv" --plot "$out/earth-shadow-at-moon.png"
echo "== Earth's shadow at the Moon's distance, through the atmosphere (earth-2015-calbuco)"
"${xvfb[@]}" "$umbra" profile shadow --occluder Earth --atmosphere earth-2015-calbuco \
  --distance 356849km --csv "$out/earth-shadow-at-moon-atmosphere.csv" --plot "$out/earth-shadow-at-moon-atmosphere.png"
echo "== the sky around the Moon, partial phase (01:30Z) and totality (02:47Z)"
sky=examples/scenes/lunar-eclipse-2015-09-28-sky.json
"${xvfb[@]}" "$umbra" render "$sky" --time 2015-09-28T01:30:00Z --output "$out/lunar-eclipse-2015-09-28-sky-partial.png"
"${xvfb[@]}" "$umbra" render "$sky" --time 2015-09-28T02:47:00Z --output "$out/lunar-eclipse-2015-09-28-sky-totality.png"
echo "== totality of the solar eclipse of 2027-08-02 from Luxor, and its sky along the vertical and the almucantar"
"${xvfb[@]}" "$umbra" render examples/scenes/solar-eclipse-2027-08-02-luxor.json \
  --output "$out/solar-eclipse-2027-08-02-luxor.png"
"$umbra" atmosphere eclipse-sky --preset earth --time 2027-08-02T10:06:00Z --observer 25.6872,32.6396,80 \
  --method fast --csv "$out/solar-eclipse-2027-08-02-luxor-sky.csv" \
  --plot-vertical "$out/solar-eclipse-2027-08-02-luxor-vertical.png" \
  --plot-almucantar "$out/solar-eclipse-2027-08-02-luxor-almucantar.png"

echo
echo "Files written:"
for f in lunar-eclipse-2015-09-28-totality.png lunar-eclipse-2015-09-28-partial.png earth-shadow-lut.exr \
  earth-shadow-at-moon.csv earth-shadow-at-moon.png earth-shadow-at-moon-atmosphere.csv \
  earth-shadow-at-moon-atmosphere.png lunar-eclipse-2015-09-28-sky-partial.png \
  lunar-eclipse-2015-09-28-sky-totality.png solar-eclipse-2027-08-02-luxor.png \
  solar-eclipse-2027-08-02-luxor-sky.csv solar-eclipse-2027-08-02-luxor-vertical.png \
  solar-eclipse-2027-08-02-luxor-almucantar.png; do
  echo "  $(cd "$out" && pwd)/$f"
done
