#!/usr/bin/env bash
# Mars' shadow at the distances of Phobos (9376 km) and Deimos (23 463 km) (eclipse paper,
# Figure 12 right): red over most of the umbra at Phobos and its inner third at Deimos, grey
# near the penumbra's boundary (docs/eclipse-shadows.md, "Mars' shadow with Lorenz-Mie dust: Figure 12 at
# Phobos and Deimos").
# Usage: examples/eclipse/mars-phobos-deimos.sh [OUTPUT_DIR]
source "$(dirname "$0")/common.sh"
for moon in phobos:9376km deimos:23463km; do
  name="${moon%%:*}" distance="${moon#*:}"
  # --exact: past the solid body's penumbra (v >= 1) every shadow LuT reads 1, while Mars'
  # atmosphere still dims the Sun there (the grey rim of the figure). Without --exact the
  # profile reads a LuT over this cross-section's distances (within 2e-4 of --exact inside
  # the solid penumbra at 64^2; docs/accuracy-vs-speed/eclipse-luts.md, "Scene-limited shadow LuTs").
  # --scattering-nu 32: the dust's forward-peaked multiple scattering needs 32 cells in nu
  # (docs/eclipse-shadows.md, "The nu resolution of the scattering tables: Mars").
  "$UMBRA" profile shadow --occluder mars --atmosphere mars --distance "$distance" --exact --scattering-nu 32 \
    --csv "$out/mars-shadow-$name.csv" --plot "$out/mars-shadow-$name.svg" "${extra[@]}"
done
