#!/usr/bin/env bash
# The eclipsed Moon's brightness at greatest eclipse for every total lunar eclipse of
# 2000-2025 through the clear `earth` atmosphere (and 2015 through `earth-2015-calbuco`):
# a table of date, gamma, predicted V and Danjon L (docs/eclipse-predictions.md).
# Usage: examples/eclipse/lunar-eclipse-brightness.sh [OUTPUT_DIR]
source "$(dirname "$0")/common.sh"
"$UMBRA" eclipses --from 2000-01-01 --to 2025-12-31 --kind lunar --csv "$out/lunar-eclipses.csv" >/dev/null
table="$out/lunar-eclipse-brightness.csv"
echo "date,atmosphere,gamma,umbral_magnitude,v,danjon_l" > "$table.tmp"
grep ',total,' "$out/lunar-eclipses.csv" | while IFS=, read -r kind type greatest _ _ _ gamma magnitude _; do
  date="${greatest:0:10}"
  atmospheres=(earth)
  [ "$date" = 2015-09-28 ] && atmospheres+=(earth-2015-calbuco)
  for atmosphere in "${atmospheres[@]}"; do
    "$UMBRA" eclipse brightness --date "$date" --atmosphere "$atmosphere" --csv "$out/b.csv" "${extra[@]}" >/dev/null
    v=$(grep '^v,' "$out/b.csv" | cut -d, -f2)
    l=$(grep '^danjon_l,' "$out/b.csv" | cut -d, -f2)
    echo "$date,$atmosphere,$gamma,$magnitude,$v,$l" | tee -a "$table.tmp"
  done
done
rm -f "$out/b.csv"
mv "$table.tmp" "$table"
echo "wrote $table"
