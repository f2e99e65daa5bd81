#!/usr/bin/env bash
# The bundle on a machine that has nothing of vgi's build: a fresh minbase Debian 12
# chroot (scripts/fresh_chroot.sh) with only Mesa's EGL runtime installed (libegl-mesa0 and
# its llvmpipe driver, as a GPU node has only its driver), the bundle unpacked under /opt.
# It renders the Cornell box with nearfield (GL) and reference (Embree) there, and the full
# build renders the same here; the images' pixels must be identical (OpenImageIO's
# iinfo --hash of each EXR). Also checks the bundle's budget (scripts/bundle.sh).
# Usage (as root): scripts/test_bundle.sh [work-dir]   (default /var/tmp/vgi-bundle)
set -euo pipefail
cd "$(dirname "$0")/.."
work=${1:-/var/tmp/vgi-bundle}
. scripts/fresh_chroot.sh
bash scripts/bundle.sh "$work/bundle"
tarball=$(ls "$work"/bundle/vgi-*-linux-x86_64.tar.xz)
root="$work/root"
fresh_root "$root"
echo "test_bundle: installing Mesa's EGL runtime only"
in_root "$root" "apt-get update -qq && apt-get install -y -qq --no-install-recommends libegl-mesa0 libgl1-mesa-dri" \
  > "$work/apt.log" 2>&1 || { tail -20 "$work/apt.log"; exit 1; }
mkdir -p "$root/opt" "$root/out"
tar -C "$root/opt" -xf "$tarball"
name=$(basename "$tarball" .tar.xz)
renders=("nearfield --gl egl" "reference --set integrator=path")
status=0
mkdir -p "$work/full"
for i in "${!renders[@]}"; do
  args="--method ${renders[$i]} --size 96x96 --spp 4 --quiet"
  if ! in_root "$root" "/opt/$name/bin/vgi render $args -o /out/r$i.exr" > "$work/r$i.log" 2>&1; then
    echo "test_bundle: FAIL: the bundle's vgi render $args"
    tail -20 "$work/r$i.log" | sed 's/^/  | /'
    status=1
    continue
  fi
  build/apps/vgi render $args -o "$work/full/r$i.exr" > /dev/null 2>&1
  a=$(iinfo --hash "$root/out/r$i.exr" | awk '/SHA-1/ {print $2}')
  b=$(iinfo --hash "$work/full/r$i.exr" | awk '/SHA-1/ {print $2}')
  renderer=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['gl_renderer'])" "$root/out/r$i.json")
  if [ -n "$a" ] && [ "$a" = "$b" ]; then
    echo "test_bundle: ${renders[$i]}: identical pixels ($a; $renderer)"
  else
    echo "test_bundle: FAIL: ${renders[$i]}: bundle $a, full build $b"
    status=1
  fi
done
[ $status -eq 0 ] && echo "test_bundle: PASS" || echo "test_bundle: FAIL"
exit $status
