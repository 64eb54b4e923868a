#!/usr/bin/env bash
# The GPU checks (paper Tables 1-2, CPU against GLSL), on EGL (no X server, no VTK
# installed), from scripts/device-kit.sh's .devkit/kit.tar.xz. On the GPU machine, with
# .devkit/ and .gl/ beside the source tree, from the repository root (about 8 minutes):
#
#   bash scripts/device-checks.sh
#
# 1. $OUT/glsl-tests.txt: the rendering tests (CPU reference against GLSL, the extremes)
#    with every window on the GPU (UMBRA_TEST_EGL=1).
# 2. $OUT/frame-times.md: the frame-time ratios of paper Tables 1-2 with GL timer queries
#    (whole frames, and the receivers' and atmosphere's stages as the paper times them),
#    ROUNDS (3) runs of FRAMES (50) interleaved frames, at 1920x1080 and 3840x2160, the
#    sunset bench, and the Moon's photometry and maps against Lambert's law (the receivers'
#    stage).
# $OUT/environment.txt: what EGL finds (vendor file, loaders). Without $OUT the files go
# to out/device/. Here (Mesa, no GPU) it runs on llvmpipe:
# `FRAMES=2 ROUNDS=1 scripts/device-checks.sh`.
set -uo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-out/device}
frames=${FRAMES:-50}
rounds=${ROUNDS:-3}
mkdir -p "$out"
[ -f .devkit/kit.tar.xz ] || { echo "device-checks: no .devkit/kit.tar.xz (run scripts/device-kit.sh, carry .devkit)" >&2; exit 1; }

# GL loaders (libglvnd) where the machine has none; the NVIDIA driver's EGL vendor file.
for lib in libEGL.so.1 libOpenGL.so.0 libGLX.so.0 libGL.so.1 libGLdispatch.so.0; do
  if ! ldconfig -p | grep -q "$lib "; then
    for f in .gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
    break
  fi
done
nvidia=$(ls /usr/local/nvidia/share/glvnd/egl_vendor.d/*nvidia*.json /usr/share/glvnd/egl_vendor.d/*nvidia*.json \
  /etc/glvnd/egl_vendor.d/*nvidia*.json 2>/dev/null | head -1)
[ -n "$nvidia" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$nvidia
# What EGL will find, for a run that fails to reach the GPU.
{
  echo "EGL vendor file: ${nvidia:-none found}"
  [ -n "$nvidia" ] && cat "$nvidia"
  ldconfig -p | grep -E 'libEGL|libGLdispatch|libOpenGL|nvidia' | head -20
  command -v nvidia-smi >/dev/null && nvidia-smi -L
} >"$out/environment.txt" 2>&1

kit=$(mktemp -d)
tar -C "$kit" -xJf .devkit/kit.tar.xz
export LD_LIBRARY_PATH=$kit/kit/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export UMBRA_CACHE_DIR=$kit/kit/cache
bin=$kit/kit/bin
# The atmosphere presets and the tests' example scenes are read from the source tree the
# kit was built in: point that path here (and the presets' own variable, in case /work
# cannot be written).
export UMBRA_ATMOSPHERE_PRESET_DIR=$PWD/atmosphere/presets
# The Moon's maps from the kit (the machine has neither Debian package).
export UMBRA_MARBLE_DATA_DIR=$kit/kit/data/marble UMBRA_STELLARIUM_DATA_DIR=$kit/kit/data/stellarium
source_dir=$(cat "$kit/kit/source-dir")
if [ ! -e "$source_dir/examples/scenes" ]; then
  mkdir -p "$(dirname "$source_dir")"
  ln -sfn "$PWD" "$source_dir"
fi

echo "== the rendering tests on EGL (CPU against GLSL) =="
{
  UMBRA_TEST_EGL=1 UMBRA_CACHE_DIR=$kit/test-cache "$bin/test_render" 2>&1
  render_status=$?
  UMBRA_TEST_EGL=1 UMBRA_CACHE_DIR=$kit/test-cache "$bin/test_pipeline" 2>&1
  pipeline_status=$?
  [ "$render_status" = 0 ] && [ "$pipeline_status" = 0 ]
} | tee "$out/glsl-tests.txt.part"
tests_status=${PIPESTATUS[0]}
mv "$out/glsl-tests.txt.part" "$out/glsl-tests.txt"

echo "== frame times =="
{
  failed=0
  echo "# umbra frame times, $(date -u +%Y-%m-%dT%H:%M:%SZ), $frames frames x $rounds rounds"
  command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,clocks.sm --format=csv,noheader
  for r in $(seq "$rounds"); do
    for size in 1920x1080 3840x2160; do
      echo
      echo "## round $r, $size: shadow and ring (eclipse paper Tables 1-2)"
      "$bin/umbra-bench-render-eclipse-atmosphere" --egl --frames "$frames" --width "${size%x*}" --height "${size#*x}" || failed=1
    done
    echo
    echo "## round $r, 1920x1080: the sunset from 2 m (atmosphere, refraction, glare)"
    "$bin/umbra-bench-render-atmosphere" --egl --frames "$frames" --tables small || failed=1
    echo
    echo "## round $r, 1920x1080: the Moon, Hapke's photometry and its maps against Lambert's law"
    "$bin/umbra-bench-render-moon" --egl --frames "$frames" || failed=1
  done
  exit "$failed"
} 2>&1 | tee "$out/frame-times.md.part"
bench_status=${PIPESTATUS[0]}
mv "$out/frame-times.md.part" "$out/frame-times.md"
rm -rf "$kit"
echo "device-checks: tests exit $tests_status, benches exit $bench_status"
[ "$tests_status" -eq 0 ] && [ "$bench_status" -eq 0 ]
