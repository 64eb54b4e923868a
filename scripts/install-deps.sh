#!/usr/bin/env bash
# Installs umbra's build and run dependencies from Debian 12 packages, and the data read
# at run time: the Moon's albedo map (the Clementine mosaic in marble-qt-data), the star
# catalogue (the Hipparcos/Tycho stars of kstars-data) and the Moon's relief (the normal map
# in stellarium-data).
# Idempotent: packages already present are not touched, and apt-get runs only when
# something is missing. Uses sudo when not run as root.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libvtk9-dev libvtk9-qt-dev qtbase5-dev
  libopenexr-dev libgeographiclib-dev libglm-dev liberfa-dev libnova-dev libboost-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev libgdal-dev
  openmpi-bin libopenmpi-dev
  xvfb xauth libgl1-mesa-dri libegl-dev libegl-mesa0
  marble-qt-data kstars-data stellarium-data
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "umbra: all ${#packages[@]} dependency packages are installed"
  exit 0
fi

echo "umbra: installing ${#missing[@]} missing packages: ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
