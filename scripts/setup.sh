#!/usr/bin/env bash
# Installs every build and run dependency from Debian packages. Idempotent:
# packages already present are skipped, so a second run costs seconds.
#   scripts/setup.sh [--tests | --demo]   --tests: also what only the suite needs (TEST_PKGS;
#   scripts/test.sh); --demo: also what only the demo needs (DEMO_PKGS; scripts/demo.sh)
set -euo pipefail
# Toolchain (clang-format for the suite's format check); libraries; Mesa's
# llvmpipe for EGL (surfaceless) and OSMesa, so the GL code runs on a machine
# without a GPU. Two packages are here only because
# Debian's CMake configs of other packages name their files: OpenImageIO's
# exported targets reference /usr/bin/iconvert (openimageio-tools), and assimp's
# link interface names libz.so (zlib1g-dev). Without them configure, then link,
# fails on a fresh Debian 12 (scripts/check_fresh_machine.sh checks that).
# libopenexr-dev, libpng-dev, libjpeg-dev and libstb-dev: the lean image layer (core/image_io.h), built
# beside OpenImageIO for its tests and alone for the bundle (scripts/bundle.sh).
# python3-matplotlib draws `vgi sweep`'s plots (scripts/sweep_report.py); the
# suite opens its HTML report in headless chromium (tests/apps/sweep_test.cpp). xvfb (+ xauth for
# xvfb-run) gives `vgi view` an X server with Mesa on a machine without a display (tests/apps/view_test.cpp).
# mesa-vulkan-drivers (lavapipe) is the suite's second GL driver, zink on Vulkan (`--gl zink`,
# scripts/driver_parity.py); glslang-tools, the Khronos reference compiler every program passes
# (tests/illum/modules_test.cpp).
PKGS=(
  build-essential cmake ninja-build pkg-config git python3 python3-glad clang-format
  libembree-dev libopenimageio-dev openimageio-tools libassimp-dev zlib1g-dev libopenmesh-dev libeigen3-dev
  libopenexr-dev libpng-dev libjpeg-dev libstb-dev
  libglfw3-dev libglm-dev libimgui-dev libcli11-dev nlohmann-json3-dev libgtest-dev
  libegl-dev libgl-dev libosmesa6-dev libegl-mesa0 libgl1-mesa-dri
  python3-matplotlib chromium xvfb xauth
  mesa-vulkan-drivers glslang-tools
)
# Only the suite's: a one-node Slurm (munge, slurmctld, slurmd, sbatch) for
# Slurm.SweepAsAJobArrayEqualsALocalSweep (scripts/test_slurm.sh starts its own daemons in a
# temporary folder; the packages' services stay off).
TEST_PKGS=(slurmctld slurmd slurm-client munge)
# Only the demo's (scripts/demo.sh): ffmpeg encodes its frames into a video.
DEMO_PKGS=(ffmpeg)
case ${1:-} in
  --tests) PKGS+=("${TEST_PKGS[@]}") ;;
  --demo) PKGS+=("${DEMO_PKGS[@]}") ;;
  "") ;;
  *) echo "setup: unknown argument '$1' (usage: scripts/setup.sh [--tests | --demo])" >&2; exit 2 ;;
esac
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PKGS[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
