#!/usr/bin/env bash
# A `vgi sweep` on a Slurm cluster: every render of the experiment as one job array (one task per
# render, each an independent `vgi render`), then the results collected from what finished.
#   scripts/sweep_slurm.sh EXPERIMENT OUT [sbatch options…]
# VGI: the vgi the tasks run (default: build/apps/vgi, or a bundle's bin/vgi on shared storage); the
# experiment's relative scene paths are the current folder's, as with `vgi sweep`. It waits for the
# array (sbatch --wait), so run it inside `salloc`/`tmux` or as a job of its own on a long sweep.
# An interrupted or partly failed array is resumed by running the script again: finished renders
# are kept (their JSON says so) and only the others are listed again.
set -euo pipefail
. "$(dirname "$0")/script_args.sh"
[ $# -ge 2 ] || sa_usage "EXPERIMENT OUT [sbatch options...]   (VGI=path/to/vgi)"
experiment=$1
out=$2
shift 2
vgi=${VGI:-build/apps/vgi}
sa_vgi VGI "$vgi"
[ -f "$experiment" ] || sa_fail EXPERIMENT "$experiment" "is not a file"
command -v sbatch > /dev/null || { echo "$sa_prog: sbatch is missing: this runs on a Slurm cluster" >&2; exit 2; }
sa_out OUT "$out"
jobs="$out/jobs.txt"
"$vgi" sweep "$experiment" -o "$out" --print-commands > "$jobs.all"  # its own error (exit 2) ends this
# Only the renders not done yet, as the sweep itself decides (a finished one's stats say so).
"$vgi" sweep "$experiment" -o "$out" --pending > "$jobs"
n=$(wc -l < "$jobs")
echo "sweep_slurm: $n of $(wc -l < "$jobs.all") renders to run"
if [ "$n" -gt 0 ]; then
  mkdir -p "$out/slurm"
  sbatch --wait --array="1-$n" --job-name=vgi-sweep --output="$out/slurm/%A_%a.log" "$@" \
    --wrap "eval \"\$(sed -n \${SLURM_ARRAY_TASK_ID}p '$jobs')\"" || echo "sweep_slurm: some tasks failed (see $out/slurm/)"
fi
"$vgi" sweep "$experiment" -o "$out" --collect
