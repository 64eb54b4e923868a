#!/usr/bin/env bash
# Frames of the total solar eclipse of 2027-08-02 seen from Luxor, Egypt, from 30 minutes
# before second contact (about 10:03 UT) to 30 minutes after third (about 10:08:40 UT), one
# a minute (or every STEP): the sky dimming with the crescent, totality (the sky of the
# umbra, the horizon's glow, the corona, the planets), and the light coming back.
#
#   scripts/solar-eclipse-animation.sh [OUT_DIR] [STEP] [EXPOSURE_EV]
#
# Defaults: out/luxor-frames, 1min, the scene's exposure (+3 EV, set for totality: the
# partial phases come out white until the last minutes, as a camera at a fixed exposure
# shows them; give e.g. -9 for the partial phases, or write .exr frames by editing the
# name below to keep the radiance for your own tone mapping). Each frame inside the
# penumbra computes its sky on the CPU: about 13 s a frame at 960x540 on 2 cores, some 15
# minutes for the 67 frames. Needs a build (scripts/build.sh) and xvfb-run.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/luxor-frames}
step=${2:-1min}
exposure=(); [ $# -ge 3 ] && exposure=(--exposure "$3")
umbra=${UMBRA_BUILD_DIR:-build}/app/cli/umbra
mkdir -p "$out"
xvfb-run -a -s "-screen 0 1280x1024x24" "$umbra" render examples/scenes/solar-eclipse-2027-08-02-luxor.json \
  --from 2027-08-02T09:33:00Z --to 2027-08-02T10:39:00Z --step "$step" "${exposure[@]}" \
  --output "$out/luxor-%04d.png"
echo "frames in $out (a video, where ffmpeg is installed: ffmpeg -framerate 10 -i $out/luxor-%04d.png luxor.mp4)"
