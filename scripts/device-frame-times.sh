#!/usr/bin/env bash
# The frame-time ratios of paper Tables 1-2 on a GPU, with GL timer queries: runs the
# render benches of scripts/device-kit.sh's .devkit/kit.tar.xz on EGL (no X server, no
# VTK installed). For the `device` tool's machine, from the repository root:
#
#   run  command: bash scripts/device-frame-times.sh   carry: [".devkit", ".gl"]   timeout_s: 480
#
# Writes $OUT/frame-times.md (out/device/ without $OUT) and prints it. ROUNDS (3) runs of
# FRAMES (50) interleaved frames each; sizes 1920x1080 and 3840x2160.
# Here (Mesa, no GPU) it runs on llvmpipe: `FRAMES=3 ROUNDS=1 scripts/device-frame-times.sh`.
set -uo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-out/device}
frames=${FRAMES:-50}
rounds=${ROUNDS:-3}
mkdir -p "$out"
[ -f .devkit/kit.tar.xz ] || { echo "device-frame-times: no .devkit/kit.tar.xz (run scripts/device-kit.sh, carry .devkit)" >&2; exit 1; }

# GL loaders (libglvnd) where the machine has none; the NVIDIA driver's EGL vendor file.
if ! ldconfig -p | grep -q 'libEGL.so.1 '; then
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
nvidia=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f "$nvidia" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$nvidia

kit=$(mktemp -d)
tar -C "$kit" -xJf .devkit/kit.tar.xz
export LD_LIBRARY_PATH=$kit/kit/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export UMBRA_CACHE_DIR=$kit/kit/cache
bin=$kit/kit/bin

{
  echo "# umbra frame times, $(date -u +%Y-%m-%dT%H:%M:%SZ), $frames frames x $rounds rounds"
  command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,clocks.sm --format=csv,noheader
  for r in $(seq "$rounds"); do
    for size in 1920x1080 3840x2160; do
      echo
      echo "## round $r, $size: shadow and ring (eclipse paper Tables 1-2)"
      "$bin/umbra-bench-render-eclipse-atmosphere" --egl --frames "$frames" --width "${size%x*}" --height "${size#*x}"
    done
    echo
    echo "## round $r, 1920x1080: the sunset from 2 m (atmosphere, refraction, glare)"
    "$bin/umbra-bench-render-atmosphere" --egl --frames "$frames" --tables small
  done
} 2>&1 | tee "$out/frame-times.md.part"
status=${PIPESTATUS[0]}
mv "$out/frame-times.md.part" "$out/frame-times.md"
rm -rf "$kit"
exit "$status"
