#!/usr/bin/env bash
# Frame pieces against the plain render on one machine (docs/scale-out.md, "What pieces cost"):
#   plain   one glint process with 2 threads writes the PNG;
#   pieces  two farm pieces, `--part 0/2` and `--part 1/2`, each one process with 1 thread, run
#           at the same time, then `glint merge` of the two into the PNG.
# Medians of RUNS runs each (hyperfine, one warm-up run each), the overhead of pieces against
# plain, the time of the merge alone, and the bytes of the piece files. Checks that the merged
# PNG is the plain one, byte for byte.
# Usage: bench/pieces.sh BUILD_DIR [RUNS] [SCENE] [GLINT_OPTIONS...]
# Default: scenes/cornell.test --integrator path --spp 64 (the scene's 512x512). Needs hyperfine.
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
opts="--integrator path --spp 64 $*"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

render="$glint -q $scene $opts"
plain="$render -t 2 -o plain.png"
# One piece in the background, one in the foreground, then the merge once both are written.
pieces="$render -t 1 --part 0/2 -o p0.exr & p=\$!; $render -t 1 --part 1/2 -o p1.exr && wait \$p && $glint merge -q -o merged.png p0.exr p1.exr"
merge="$glint merge -q -o merged.png p0.exr p1.exr"

echo "== $(basename "$scene") $opts; glint $("$glint" --version | cut -d' ' -f2-)"
hyperfine --style basic --runs "$runs" --warmup 1 --export-json times.json \
    -n plain "$plain" -n pieces "$pieces" -n merge "$merge"
cmp plain.png merged.png && echo "merged.png is plain.png, byte for byte"

python3 - "$runs" <<'EOF'
import json, os, sys
r = {x["command"]: x for x in json.load(open("times.json"))["results"]}
plain, pieces, merge = (r[k]["median"] for k in ("plain", "pieces", "merge"))
print(f"medians of {sys.argv[1]} runs: plain {plain:.3f} s, pieces + merge {pieces:.3f} s "
      f"(overhead {100 * (pieces / plain - 1):+.1f}%), merge alone {merge:.3f} s")
for f in ("p0.exr", "p1.exr", "merged.png"):
    print(f"{f}: {os.path.getsize(f)} bytes")
EOF
