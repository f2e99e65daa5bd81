#!/usr/bin/env bash
# Loading time against triangle count on coincident geometry (issue 33, class 10), the table
# "Loading meshes with coincident geometry" of docs/BENCHMARKS.md: `vgi info` (load, generate
# normals, check the scene) on OBJs without normals of 10^3 … 10^6 triangles of four kinds:
#   copies  N copies of one triangle (3 positions of N corners each)
#   disc    N coplanar triangles around one vertex (one position of N corners, one normal)
#   cone    N facets around an apex (N distinct normals at one position: flat beyond 1024)
#   grid    a height field of N triangles (ordinary geometry, for scale)
# Wall time and peak resident memory of the process, one run each.
# Usage: scripts/bench_load.sh [out-dir] [max-triangles]   (VGI=path/to/vgi)
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/script_args.sh
[ $# -le 2 ] || sa_usage "[out-dir] [max-triangles]   (VGI=path/to/vgi)"
out=${1:-out/bench_load}
max=${2:-1000000}
vgi=${VGI:-build/apps/vgi}
sa_vgi VGI "$vgi"
sa_int max-triangles "$max"
sa_out out-dir "$out"
python3 - "$out" "$max" "$vgi" <<'EOF'
import math, os, random, resource, subprocess, sys, time
out, top, vgi = sys.argv[1], int(sys.argv[2]), sys.argv[3]

def write(path, kind, n):
    with open(path, "w") as f:
        w = f.write
        if kind == "copies":
            w("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
            w("f 1 2 3\n" * n)
        elif kind in ("disc", "cone"):
            w("v 0 0 %d\n" % (kind == "cone"))
            w("".join("v %.9g %.9g 0\n" % (math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n)) for i in range(n + 1)))
            w("".join("f 1 %d %d\n" % (i + 2, i + 3) for i in range(n)))
        else:
            m = int(math.sqrt(n / 2)) + 1
            r = random.Random(1)
            w("".join("v %d %d %.4f\n" % (i, j, 0.3 * r.random()) for i in range(m) for j in range(m)))
            w("".join("f %d %d %d\nf %d %d %d\n" % (i * m + j + 1, (i + 1) * m + j + 1, i * m + j + 2,
                                                      (i + 1) * m + j + 1, (i + 1) * m + j + 2, i * m + j + 2)
                      for i in range(m - 1) for j in range(m - 1)))

def run(path):
    """Wall seconds and peak resident MiB of `vgi info --scene path`."""
    t0 = time.monotonic()
    pid = os.fork()
    if pid == 0:
        fd = os.open(path + ".log", os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(fd, 1)
        os.dup2(fd, 2)
        os.execv(vgi, [vgi, "info", "--scene", path])
    _, status, usage = os.wait4(pid, 0)
    if status != 0:  # vgi's own reason, from its log
        lines = [l for l in open(path + ".log", errors="replace").read().splitlines() if l.strip()]
        reason = ([l for l in lines if "vgi: error:" in l] or lines or ["(no output)"])[-1]
        sys.exit("bench_load.sh: FAILED: vgi info --scene %s (status %d): %s" % (path, status, reason))
    return time.monotonic() - t0, usage.ru_maxrss / 1024.0

sizes = [n for n in (1000, 10000, 100000, 1000000) if n <= top]
kinds = ("copies", "disc", "cone", "grid")
print("| triangles | " + " | ".join(k + ": s, MiB" for k in kinds) + " |")
print("|---:|" + "---:|" * len(kinds))
for n in sizes:
    cells = []
    for kind in kinds:
        path = os.path.join(out, "%s_%d.obj" % (kind, n))
        if not os.path.exists(path):
            write(path, kind, n)
        cells.append("%.2f, %.0f" % run(path))
    print("| %d | %s |" % (n, " | ".join(cells)), flush=True)
EOF
