#!/bin/sh
# What the glTF layer extensions cost: each Khronos model rendered at a fixed sample count
# (an explicit --spp: no adaptive stop; no denoiser) as it is and without its layer extensions
# (strip_layers.py), interleaved, median of RUNS; prints the times and their ratio.
#   bench/materials/layers.sh build/glint [SPP] [RUNS]
set -eu
GLINT=$1
SPP=${2:-16}
RUNS=${3:-3}
ASSETS=${GLINT_ASSETS:-$(dirname "$0")/../../../shared/real-world/gltf-ext}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
seconds() {  # wall seconds of one render
    start=$(date +%s.%N)
    "$GLINT" "$1" --spp "$SPP" --no-denoise -q -o "$TMP/out.png" 2>/dev/null
    end=$(date +%s.%N)
    echo "$end - $start" | bc -l
}
printf '%-22s %10s %10s %7s\n' model layered plain ratio
for model in ClearCoatTest SheenChair SpecularTest AnisotropyBarnLamp IridescenceLamp; do
    gltf=$ASSETS/$model/glTF/$model.gltf
    [ -f "$gltf" ] || continue
    rm -rf "$TMP/model"
    cp -r "$ASSETS/$model/glTF" "$TMP/model"
    python3 "$(dirname "$0")/strip_layers.py" "$gltf" "$TMP/model/plain.gltf"
    : >"$TMP/a"
    : >"$TMP/b"
    i=0
    while [ $i -lt "$RUNS" ]; do
        seconds "$gltf" >>"$TMP/a"
        seconds "$TMP/model/plain.gltf" >>"$TMP/b"
        i=$((i + 1))
    done
    a=$(median <"$TMP/a")
    b=$(median <"$TMP/b")
    printf '%-22s %10.2f %10.2f %7.2f\n' "$model" "$a" "$b" "$(echo "$a / $b" | bc -l)"
done
