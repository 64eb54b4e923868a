#!/usr/bin/env bash
# Packs what the GPU checks need on a machine that has no VTK, no X server and no package
# mirror (a GPU machine; docs/accuracy-vs-speed/rendering.md, "Frame-time ratios on a
# GPU"): .devkit/kit.tar.xz with the three frame-time benches, the rendering tests (CPU
# against GLSL), the shared libraries they load (all but glibc >= 2.36,
# libstdc++ and the GL loaders), the benches' small tables from the cache, the Moon's two
# maps (a copy of the files that marble-qt-data and stellarium-data install here); and .gl/ with
# Debian's GL loader packages (libglvnd: libEGL, libOpenGL). scripts/device-checks.sh runs
# them there.
#
#   scripts/device-kit.sh [BUILD_DIR]      (default: build; builds the benches first)
#
# Both .devkit/ and .gl/ are ignored by git; copy them with the source tree to the GPU machine.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
benches=(umbra-bench-render-eclipse-atmosphere umbra-bench-render-atmosphere umbra-bench-render-moon)
programs=("${benches[@]}" test_render test_pipeline)
paths=("$build/bench/${benches[0]}" "$build/bench/${benches[1]}" "$build/bench/${benches[2]}"
       "$build/tests/render/test_render" "$build/tests/pipeline/test_pipeline")
# The Moon's albedo and normal maps, as the Moon bench's scene names them (its receivers'
# stage with both is what the GPU is to time): under the kit's data/, for
# UMBRA_MARBLE_DATA_DIR and UMBRA_STELLARIUM_DATA_DIR there.
maps=(marble/maps/moon/clementine/clementine.jpg stellarium/textures/moon_normals.png)
map_sources=("${UMBRA_MARBLE_DATA_DIR:-/usr/share/marble/data}/maps/moon/clementine/clementine.jpg"
             "${UMBRA_STELLARIUM_DATA_DIR:-/usr/share/stellarium}/textures/moon_normals.png")
for f in "${map_sources[@]}"; do
  [ -f "$f" ] || { echo "device-kit: no $f (scripts/install-deps.sh installs marble-qt-data and stellarium-data)" >&2; exit 1; }
done

[ -f "$build/build.ninja" ] || { echo "device-kit: no Ninja build in $build (configure it first)" >&2; exit 1; }
ninja -C "$build" "${programs[@]}"

stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/kit/bin" "$stage/kit/lib" "$stage/kit/cache"
for p in "${paths[@]}"; do cp "$p" "$stage/kit/bin/"; done
for i in "${!maps[@]}"; do
  mkdir -p "$stage/kit/data/$(dirname "${maps[$i]}")"
  cp "${map_sources[$i]}" "$stage/kit/data/${maps[$i]}"
done
# The tests read the example scenes from the source tree they were built in.
pwd >"$stage/kit/source-dir"

# Shared libraries, resolved here (Debian 12); the machine's own glibc, libstdc++ and GL
# loaders (with the NVIDIA driver behind them) are used there.
skip='^(linux-vdso|ld-linux|libc\.|libm\.|libdl\.|libpthread\.|librt\.|libstdc\+\+|libgcc_s|libGL\.|libGLX\.|libGLdispatch\.|libEGL\.|libOpenGL\.)'
for p in "${paths[@]}"; do ldd "$p"; done | awk '/=> \// {print $1, $3}' | sort -u |
  while read -r name path; do
    [[ $name =~ $skip ]] || cp -L "$path" "$stage/kit/lib/$name"
  done

# Every library a program loads comes from the kit, except those the machine brings.
for p in "$stage"/kit/bin/*; do
  LD_LIBRARY_PATH="$stage/kit/lib" ldd "$p" | awk '/=> \// {print $1, $3}' |
    while read -r name path; do
      if [[ ! $name =~ $skip && $path != "$stage/kit/lib/"* ]]; then
        echo "device-kit: $(basename "$p") loads $path from outside the kit" >&2
        exit 1
      fi
    done || exit 1
done

# The tables of the frame-time runs (small sizes), made here so that the GPU's minutes go
# to the frames. Earth's default-size tables too, for the sunset bench.
echo "device-kit: filling the table cache (small tables; minutes on first use)"
UMBRA_CACHE_DIR="$stage/kit/cache" xvfb-run -a "$build/bench/umbra-bench-render-eclipse-atmosphere" \
  --frames 1 --width 64 --height 36 >/dev/null
UMBRA_CACHE_DIR="$stage/kit/cache" xvfb-run -a "$build/bench/umbra-bench-render-atmosphere" \
  --frames 1 --width 64 --height 36 --tables small >/dev/null
UMBRA_CACHE_DIR="$stage/kit/cache" xvfb-run -a "$build/bench/umbra-bench-render-moon" \
  --frames 1 --width 64 --height 36 >/dev/null

mkdir -p .devkit
tar -C "$stage" -cJf .devkit/kit.tar.xz.part kit
mv .devkit/kit.tar.xz.part .devkit/kit.tar.xz

# The GL loaders (Debian's packages, unpacked on the GPU machine).
mkdir -p .gl
(cd .gl && apt-get download libegl1 libglvnd0 libopengl0 libgl1 libglx0 >/dev/null)
echo "device-kit: .devkit/kit.tar.xz ($(du -h .devkit/kit.tar.xz | cut -f1)), .gl/ ($(du -sh .gl | cut -f1))"
