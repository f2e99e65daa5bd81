#!/usr/bin/env bash
# The demo: Sibenik with the camera dollying down the nave and a spot light moving along it
# (scenes/sibenik-demo.json: a camera path and a light path), rendered with the default method
# (nearfield) as FRAMES frames into OUT_DIR (frame_NNNN.exr / .png) and encoded beside them as
# OUT_DIR/demo.mp4 (H.264, 24 frames per second; ffmpeg from Debian, installed by
# `scripts/setup.sh --demo` when missing).
#   bash scripts/demo.sh [OUT_DIR] [FRAMES] [SIZE] [SPP] [VGI]
#   defaults: demo 48 640x360 4 build/apps/vgi (about 4 minutes on 2 cores with llvmpipe)
set -euo pipefail
. "$(dirname "$0")/script_args.sh"
[ $# -le 5 ] || sa_usage "[OUT_DIR] [FRAMES] [SIZE] [SPP] [VGI]"
out=${1:-demo}
frames=${2:-48}
size=${3:-640x360}
spp=${4:-4}
vgi=${5:-build/apps/vgi}
root="$(cd "$(dirname "$0")/.." && pwd)"
sa_out OUT_DIR "$out"
sa_int FRAMES "$frames"
[[ "$size" =~ ^[1-9][0-9]{0,4}x[1-9][0-9]{0,4}$ ]] || sa_fail SIZE "$size" "expected WIDTHxHEIGHT"
sa_int SPP "$spp"
sa_vgi VGI "$vgi"
[ -e "$root/../shared/scenes/sibenik/sibenik.obj" ] ||
  sa_fail scene "$root/../shared/scenes/sibenik/sibenik.obj" "is absent (the demo renders Sibenik)"
command -v ffmpeg > /dev/null || bash "$root/scripts/setup.sh" --demo
# The path's time runs 0 … 1 over the frames.
step=$(awk -v n="$frames" 'BEGIN { printf "%.9g", (n > 1 ? 1 / (n - 1) : 1) }')
sa_run "$out/render.log" "$vgi" render --scene "$root/scenes/sibenik-demo.json" --size "$size" --spp "$spp" \
  --frames "$frames" --time-step "$step" --quiet -o "$out/frame.exr"
sa_run "$out/ffmpeg.log" ffmpeg -y -loglevel error -framerate 24 -i "$out/frame_%04d.png" -c:v libx264 \
  -pix_fmt yuv420p -crf 18 "$out/demo.mp4"
echo "$sa_prog: $frames frames in $out (frame_NNNN.exr/.png, frame.json), the video $out/demo.mp4"
