# Sourced by scripts/check_fresh_machine.sh and scripts/test_bundle.sh: a fresh
# Debian 12 — a `debootstrap --variant=minbase bookworm` system built once and
# cached as a tarball ($VGI_FRESH_CACHE, default /var/cache/vgi/bookworm-minbase.tar),
# unpacked anew for every run, so no run sees what an earlier one installed.
#   fresh_root DIR         unpacks it into DIR (as root), mounts proc/sys/dev, unmounts at exit
#   in_root DIR COMMAND…   runs a bash command line in it with a clean environment
# Needs root and network access to Debian's mirror ($VGI_DEBIAN_MIRROR).
fresh_root() {
  local root=$1
  local cache=${VGI_FRESH_CACHE:-/var/cache/vgi/bookworm-minbase.tar}
  local mirror=${VGI_DEBIAN_MIRROR:-http://deb.debian.org/debian}
  [ "$(id -u)" -eq 0 ] || { echo "$0: run as root (debootstrap and chroot need it)" >&2; exit 2; }
  if [ ! -f "$cache" ]; then
    command -v debootstrap > /dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap
    mkdir -p "$(dirname "$cache")"
    local base
    base=$(mktemp -d /var/tmp/vgi-minbase.XXXXXX)
    echo "$0: building the minbase Debian 12 system (once) in $base"
    debootstrap --variant=minbase bookworm "$base" "$mirror" > "$base.log" 2>&1 || { tail -20 "$base.log"; exit 1; }
    tar -C "$base" -cf "$cache.part" . && mv "$cache.part" "$cache"
    rm -rf "$base" "$base.log"
  fi
  FRESH_ROOT=$root
  trap fresh_unmount EXIT
  fresh_unmount
  rm -rf "$root"
  mkdir -p "$root"
  tar -C "$root" -xf "$cache"
  # A Debian system's / is 755; the cache's top entry came from mktemp's 700 folder, and with it no
  # user but root could reach /bin/sh (munge's postinst, `su munge`, failed on it).
  chmod 755 "$root"
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  mount -t proc proc "$root/proc"
  mount --rbind /sys "$root/sys"
  mount --bind /dev "$root/dev"
  mount --bind /dev/pts "$root/dev/pts"
}

fresh_unmount() {
  [ -n "${FRESH_ROOT:-}" ] || return 0
  for m in dev/pts dev proc sys; do mountpoint -q "$FRESH_ROOT/$m" && umount -l "$FRESH_ROOT/$m"; done
  return 0
}

in_root() {
  local root=$1
  shift
  chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    TERM=dumb LANG=C.UTF-8 DEBIAN_FRONTEND=noninteractive /bin/bash -c "$*"
}
