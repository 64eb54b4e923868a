#!/usr/bin/env bash
# Mars' shadow at the distances of Phobos (9376 km) and Deimos (23 463 km) (eclipse paper,
# Figure 12 right): red in most of the shadow, grey near the penumbra's boundary.
# Usage: examples/eclipse/mars-phobos-deimos.sh [OUTPUT_DIR]
source "$(dirname "$0")/common.sh"
for moon in phobos:9376km deimos:23463km; do
  name="${moon%%:*}" distance="${moon#*:}"
  # The moons sit where a whole LuT gives the penumbra a few rows: the profile command then
  # builds one over this cross-section's distances only (docs/eclipse-shadows.md); 64^2
  # is within 2e-4 of --exact inside the solid body's penumbra (docs/accuracy-vs-speed.md).
  size=(--size 64)
  [[ " ${extra[*]} " == *" --size "* ]] && size=()
  "$UMBRA" profile shadow --occluder mars --atmosphere mars --distance "$distance" "${size[@]}" \
    --csv "$out/mars-shadow-$name.csv" --plot "$out/mars-shadow-$name.svg" "${extra[@]}"
done
