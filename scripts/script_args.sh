# What every measurement script a reader is told to run does with its arguments and with vgi's failures,
# written once (the shell side of scripts/script_args.py): arguments are checked up front (exit 2, naming
# the argument and the value), and a vgi command that fails is reported with the reason vgi gave (its
# "vgi: error: …" line), never swallowed. Source it: . "$(dirname "$0")/script_args.sh"
sa_prog=$(basename "$0")

# sa_fail ARG VALUE WHY: the user's mistake, exit 2.
sa_fail() {
  echo "$sa_prog: error: $1 '$2': $3" >&2
  exit 2
}

# sa_usage TEXT: wrong number of arguments, exit 2.
sa_usage() {
  echo "usage: $sa_prog $1" >&2
  exit 2
}

# sa_vgi ARG PATH: PATH is a runnable vgi.
sa_vgi() {
  [ -e "$2" ] || sa_fail "$1" "$2" "does not exist (build it: bash scripts/build.sh, then build/apps/vgi)"
  [ -d "$2" ] && sa_fail "$1" "$2" "is a folder, not the vgi program"
  [ -x "$2" ] || sa_fail "$1" "$2" "is not executable"
  return 0
}

# sa_out ARG DIR: DIR is a folder this script may write into (made if missing).
sa_out() {
  [ -e "$2" ] && [ ! -d "$2" ] && sa_fail "$1" "$2" "exists and is not a folder"
  mkdir -p -- "$2" 2>/dev/null || sa_fail "$1" "$2" "cannot be made"
  [ -w "$2" ] || sa_fail "$1" "$2" "is not writable"
  return 0
}

# sa_int ARG VALUE: a positive whole number.
sa_int() {
  [[ "$2" =~ ^[1-9][0-9]{0,8}$ ]] || sa_fail "$1" "$2" "expected a positive whole number"
}

# sa_number ARG VALUE: a positive decimal number (0.25, 1e-3).
sa_number() {
  [[ "$2" =~ ^([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$ ]] && awk -v x="$2" 'BEGIN { exit !(x > 0) }' ||
    sa_fail "$1" "$2" "expected a positive number"
}

# sa_run LOG CMD...: runs a vgi command, its output into LOG; when it fails, says which command, its exit
# status and the reason vgi gave, and exits 1.
sa_run() {
  local log=$1 rc=0
  shift
  "$@" > "$log" 2>&1 || rc=$?
  if [ "$rc" != 0 ]; then
    local reason
    reason=$(grep 'vgi: error:' "$log" | tail -1)
    [ -n "$reason" ] || reason=$(grep -v '^[[:space:]]*$' "$log" | tail -1)
    echo "$sa_prog: FAILED: $*" >&2
    echo "  exit $rc: ${reason:-(no output)} (log: $log)" >&2
    exit 1
  fi
}
