#!/usr/bin/env bash
# Runs the README's two commands, exactly as the README writes them, on a fresh
# Debian 12: a `debootstrap --variant=minbase bookworm` chroot that has nothing
# but the base system, with a clean clone of HEAD (committed work only, no
# build/, no ../shared) as the working copy. It reports each command's time and
# exit status and the test summary. A package that a development machine keeps
# from a hand install, and that scripts/setup.sh forgets, fails here.
#
# The minbase system is built once and cached (scripts/fresh_chroot.sh); every
# run unpacks it anew, so no run sees what an earlier one installed.
#
# Usage (as root): scripts/check_fresh_machine.sh [work-dir]   (default /var/tmp/vgi-fresh)
# Needs: debootstrap (installed here if missing), network access to Debian's mirror.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
work=${1:-/var/tmp/vgi-fresh}
. scripts/fresh_chroot.sh

# The README's two commands: the non-comment lines of the first ```sh block
# after the "## Two commands" heading.
mapfile -t commands < <(awk '/^## Two commands/ {s = 1} s && /^```sh/ {b = 1; next} b && /^```/ {exit}
                             b && NF && !/^#/ {print}' README.md)
if [ ${#commands[@]} -ne 2 ]; then
  echo "check_fresh_machine: expected 2 commands in README.md's 'Two commands' block, found ${#commands[@]}" >&2
  exit 2
fi

root="$work/root"
fresh_root "$root"  # unmounts a previous run's mounts before it removes anything
git clone -q --no-local "$repo" "$root/root/vgi"
echo "check_fresh_machine: HEAD $(git -C "$repo" rev-parse --short HEAD), $(git -C "$repo" status --porcelain | wc -l) uncommitted change(s) not included"

status=0
for i in 0 1; do
  log="$work/command$((i + 1)).log"
  echo "check_fresh_machine: command $((i + 1)): ${commands[$i]}"
  start=$(date +%s)
  rc=0
  in_root "$root" "cd /root/vgi && ${commands[$i]}" > "$log" 2>&1 || rc=$?
  secs=$(($(date +%s) - start))
  echo "  exit $rc after ${secs} s (log: $log)"
  [ $i -eq 0 ] && grep -E '^wrote ' "$log" | sed 's/^/  /' || true
  [ $i -eq 1 ] && grep -E 'tests passed|tests failed' "$log" | sed 's/^/  /' || true
  if [ $rc -ne 0 ]; then
    tail -30 "$log" | sed 's/^/  | /'
    status=1
  fi
done
if [ $status -eq 0 ]; then
  echo "check_fresh_machine: PASS (both README commands on a fresh minbase Debian 12)"
else
  echo "check_fresh_machine: FAIL"
fi
exit $status
