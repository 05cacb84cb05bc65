#!/usr/bin/env bash
# Frame pieces against the plain render on one machine (docs/scale-out.md, "What pieces cost"):
#   plain   one glint process with 2 threads writes the PNG;
#   pieces  two farm pieces, `--part 0/2` and `--part 1/2`, each one process with 1 thread, run
#           at the same time, then `glint merge` of the two into the PNG.
# RUNS runs of each, alternating (plain, pieces, plain, ...) so that a shared machine's
# changing load falls on both alike, after one warm-up run of each. Prints the medians of wall
# time and of CPU time (user + system, of every process), the overhead of pieces against plain,
# the merge alone (hyperfine), and the bytes of the piece files; checks that the merged PNG is
# the plain one, byte for byte.
# Usage: bench/pieces.sh BUILD_DIR [RUNS] [SCENE] [GLINT_OPTIONS...]
# Default: scenes/cornell.test --integrator path --spp 64 (the scene's 512x512); GLINT_OPTIONS
# replace --spp 64. Needs hyperfine.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BUILD_DIR [RUNS] [SCENE] [GLINT_OPTIONS...]" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
glint=$(cd "$1" && pwd)/glint
runs=${2:-5}
scene=$(realpath "${3:-$here/../scenes/cornell.test}")
shift $(($# < 3 ? $# : 3))
opts="--integrator path ${*:---spp 64}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

render="$glint -q $scene $opts"
plain="$render -t 2 -o plain.png"
# One piece in the background, one in the foreground, then the merge once both are written.
pieces="$render -t 1 --part 0/2 -o p0.exr & p=\$!; $render -t 1 --part 1/2 -o p1.exr && wait \$p && $glint merge -q -o merged.png p0.exr p1.exr"

# One timed run of `bash -c CMD`: appends "wall user+system" to FILE (the children's CPU time
# is counted: bash waits for them).
timed() { /usr/bin/time -f "%e %U %S" -a -o "$1.raw" bash -c "$2"; }

echo "== $(basename "$scene") $opts; $("$glint" --version)"
timed warm "$plain"
timed warm "$pieces"
for ((i = 0; i < runs; i++)); do
    timed plain "$plain"
    timed pieces "$pieces"
done
cmp plain.png merged.png && echo "merged.png is plain.png, byte for byte"
hyperfine --style basic --runs "$runs" --export-json merge.json \
    -n merge "$glint merge -q -o merged.png p0.exr p1.exr" >/dev/null

python3 - "$runs" <<'EOF'
import json, os, statistics, sys
def runs(name):
    rows = [l.split() for l in open(name + ".raw") if l.strip() and l[0].isdigit()]
    return ([float(r[0]) for r in rows], [float(r[1]) + float(r[2]) for r in rows])
(pw, pc), (qw, qc) = runs("plain"), runs("pieces")
mw = json.load(open("merge.json"))["results"][0]["median"]
m = statistics.median
print(f"medians of {sys.argv[1]} runs each:")
print(f"  plain   (1 process, 2 threads)          wall {m(pw):7.2f} s   CPU {m(pc):7.2f} s")
print(f"  pieces  (2 processes x 1 thread, merged) wall {m(qw):7.2f} s   CPU {m(qc):7.2f} s")
print(f"  overhead of pieces + merge: wall {100 * (m(qw) / m(pw) - 1):+.1f}%, "
      f"CPU {100 * (m(qc) / m(pc) - 1):+.1f}%")
print(f"  merge alone (hyperfine median): {1000 * mw:.0f} ms")
print("  wall, each run: plain " + " ".join(f"{x:.2f}" for x in pw) +
      "; pieces " + " ".join(f"{x:.2f}" for x in qw))
for f in ("p0.exr", "p1.exr", "merged.png"):
    print(f"  {f}: {os.path.getsize(f)} bytes")
EOF
