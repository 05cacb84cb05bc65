#!/usr/bin/env bash
# Light sampling, two builds of glint against each other (docs/performance.md, section 13): the
# five scenes of the denoising benchmark at 16 spp, 320x240, 2 threads; for each, the median of
# 3 wall times (the two builds interleaved, so that both meet the same load) and the relMSE
# against the 4096-spp references of bench/denoise/make_data.sh. Efficiency is 1 / (relMSE x
# time). The references are unbiased whichever build rendered them.
# Usage: bench/light_sampling.sh OLD_GLINT NEW_GLINT DATA_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
old=${1:?old glint} new=${2:?new glint} data=${3:?data dir with NAME_ref.pfm}
m=$here/../../shared/real-world/gltf
relmse=$here/denoise/relmse.py
declare -A input=([glass]=$here/denoise/glass.test [room]=$here/denoise/room.test [lamps]=$here/denoise/lamps.test [helmet]=$m/DamagedHelmet/glTF-Binary/DamagedHelmet.glb [bottle]=$m/WaterBottle/glTF/WaterBottle.gltf)
out=$(mktemp -d)
for name in glass room lamps helmet bottle; do
  for which in old new; do
    bin=${!which}
    ts=()
    for run in 1 2 3; do
      s=$(date +%s.%N)
      "$bin" "${input[$name]}" --size 320x240 --spp 16 --no-denoise -t 2 -q -o "$out/${which}_$name.pfm" 2>/dev/null
      e=$(date +%s.%N)
      ts+=($(echo "$e - $s" | bc))
    done
    t=$(printf '%s\n' "${ts[@]}" | sort -n | sed -n 2p)
    r=$(python3 "$relmse" "$out/${which}_$name.pfm" "$data/${name}_ref.pfm")
    echo "$name $which time $t relMSE $r"
  done
done
