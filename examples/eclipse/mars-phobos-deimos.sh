#!/usr/bin/env bash
# Mars' shadow at the distances of Phobos (9376 km) and Deimos (23 463 km) (eclipse paper,
# Figure 12 right): red in most of the shadow, grey near the penumbra's boundary.
# Usage: examples/eclipse/mars-phobos-deimos.sh [OUTPUT_DIR]
source "$(dirname "$0")/common.sh"
for moon in phobos:9376km deimos:23463km; do
  name="${moon%%:*}" distance="${moon#*:}"
  # --exact: the moons sit in the first texels of the LuT's u axis (docs/accuracy-vs-speed.md).
  "$UMBRA" profile shadow --occluder mars --atmosphere mars --distance "$distance" --exact \
    --csv "$out/mars-shadow-$name.csv" --plot "$out/mars-shadow-$name.svg" "${extra[@]}"
done
