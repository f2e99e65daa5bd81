#!/usr/bin/env bash
# The relocatable bundle: OUT/vgi-<version>-linux-x86_64.tar.xz, which runs on a
# machine that has only a GL driver (an NVIDIA GPU node, or Mesa) and glibc:
#   bin/vgi            the lean build (core/image_io.h: OpenEXR, libpng, libjpeg and stb_image instead
#                      of OpenImageIO; OSMesa loaded only when --gl osmesa is chosen), RPATH $ORIGIN/../lib
#   lib/               its run-time closure (ldd), without glibc and without the GL vendor drivers:
#                      glvnd's libEGL / libOpenGL / libGLdispatch are inside and load the machine's driver
#   share/vgi/shaders  read at run time (../share/vgi/shaders beside the binary)
#   share/doc/vgi/     README and the licence (Debian copyright file) of every package it carries
# Every method, the voxelizers and the Embree reference are inside. Budget: 32 MiB compressed.
# Usage: scripts/bundle.sh [OUT]   (default out/bundle; builds build-lean/ first)
# Test: scripts/test_bundle.sh unpacks it in a fresh minbase Debian 12 chroot with Mesa's EGL only.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/bundle}
budget=$((32 * 1024 * 1024))
cmake -S . -B build-lean -G Ninja -DCMAKE_BUILD_TYPE=Release -DVGI_LEAN_IMAGES=ON -DVGI_BUILD_TESTS=OFF \
  "-DCMAKE_EXE_LINKER_FLAGS=-Wl,--disable-new-dtags" "-DCMAKE_BUILD_RPATH=\$ORIGIN/../lib" > build-lean.log 2>&1 ||
  { cat build-lean.log; exit 1; }
cmake --build build-lean --target vgi >> build-lean.log 2>&1 || { tail -30 build-lean.log; exit 1; }
bin=build-lean/apps/vgi
version=$("$bin" --version | awk 'NR == 1 {print $2}')
name=vgi-$version-linux-x86_64
stage=$out/$name
rm -rf "$stage"
mkdir -p "$stage/bin" "$stage/lib" "$stage/share/vgi" "$stage/share/doc/vgi/licenses"
cp "$bin" "$stage/bin/vgi"
strip "$stage/bin/vgi"
cp -r shaders "$stage/share/vgi/shaders"
# The driver parity set rendered here on llvmpipe: scripts/gpu_bench.sh compares a GPU's images with
# these (its parity section), so the first GPU session says "same image" or lists the differences.
python3 scripts/driver_parity.py render --vgi "$bin" --gl egl "$stage/share/vgi/parity-llvmpipe" \
  > "$out/parity-llvmpipe.log" 2>&1 || { tail -30 "$out/parity-llvmpipe.log"; exit 1; }
rm -f "$stage"/share/vgi/parity-llvmpipe/*.png "$stage"/share/vgi/parity-llvmpipe/*.log

# The closure: every library ldd resolves, but glibc's (the node's own, ABI-stable) — the
# GL vendor drivers are not in it (glvnd's libEGL / libOpenGL load them at run time).
is_glibc() {
  case "$(basename "$1")" in
    ld-linux*|libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|libresolv.so*|libutil.so*) return 0 ;;
  esac
  return 1
}
declare -A packages=()
while read -r lib; do
  is_glibc "$lib" && continue
  cp -L "$lib" "$stage/lib/"
  strip --strip-unneeded "$stage/lib/$(basename "$lib")" 2>/dev/null || true
  pkg=$(dpkg -S "$(readlink -f "$lib")" 2>/dev/null | head -1 | cut -d: -f1) ||
    pkg=$(dpkg -S "$lib" 2>/dev/null | head -1 | cut -d: -f1) || true
  [ -n "$pkg" ] && packages[$pkg]=1
done < <(ldd "$bin" | awk '$2 == "=>" && $3 ~ /^\// {print $3}')
for pkg in "${!packages[@]}"; do
  [ -f "/usr/share/doc/$pkg/copyright" ] && cp "/usr/share/doc/$pkg/copyright" "$stage/share/doc/vgi/licenses/$pkg"
done
cp LICENSE "$stage/share/doc/vgi/licenses/vgi" 2>/dev/null || true
cat > "$stage/share/doc/vgi/README" <<EOF
vgi $version — the relocatable bundle (scripts/bundle.sh of the vgi repository).

Runs where glibc >= 2.36 (Debian 12) and a GL 4.5 driver are: an NVIDIA driver (EGL device
platform) or Mesa (libegl-mesa0 + libgl1-mesa-dri: llvmpipe on the CPU). Unpack anywhere:

  tar xf $name.tar.xz
  $name/bin/vgi render --method nearfield -o cornell.exr

On a machine whose EGL vendor files are not at /usr/share/glvnd/egl_vendor.d (an NVIDIA driver
installed without glvnd, a container), point glvnd at the driver's file:
  export __EGL_VENDOR_LIBRARY_FILENAMES=/path/to/10_nvidia.json
--gl osmesa needs the machine's libOSMesa.so.8 (not carried: Mesa's LLVM is 100 MB).
lib/ holds the libraries vgi needs besides glibc and the GL driver; licenses/ the licence of
each Debian package they come from. Images: OpenEXR + libpng + libjpeg + stb_image (the same
pixels as the full build's OpenImageIO).
EOF
tar -C "$out" -cf - "$name" | xz -9 -T2 > "$out/$name.tar.xz"
size=$(stat -c %s "$out/$name.tar.xz")
echo "bundle: $out/$name.tar.xz: $((size / 1024)) KiB compressed ($(du -sk "$stage" | cut -f1) KiB unpacked," \
  "$(ls "$stage/lib" | wc -l) libraries, ${#packages[@]} packages)"
if [ "$size" -gt "$budget" ]; then
  echo "bundle: over the 32 MiB budget; the largest libraries:" >&2
  du -b "$stage/lib"/* | sort -rn | head -10 >&2
  exit 1
fi
