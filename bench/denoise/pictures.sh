#!/usr/bin/env bash
# The pictures of docs/clean-images.md ("Beside the references"): for seven scenes of the
# benchmark at 16 spp, raw | Glint's filter (nlm) | the network (oidn balanced) | the 4096-spp
# reference, as the model mode shows them (denoise_eval png=), the small models cropped and
# enlarged twice.
# Usage: bench/denoise/pictures.sh BUILD_DIR DATA_DIR OUT_DIR   (DATA_DIR from make_data.sh)
set -euo pipefail
build=${1:?build dir}
data=${2:?data dir}
out=${3:?output dir}
mkdir -p "$out"
declare -A crop=(
    [vase]=80,45,160,140,2 [toycar]=0,0,320,240,1 [chair]=80,45,160,125,2
    [helmet]=100,60,120,140,2 [cloth]=75,75,160,120,2 [caustic]=0,0,320,240,1
    [room]=0,0,320,240,1
)
for name in vase toycar chair helmet cloth caustic room; do
    "$build/bench/denoise_eval" "$data" "$name" 16 denoiser=oidn out=none \
        png="$out/network-$name.png" crop="${crop[$name]}" >/dev/null
    echo "$out/network-$name.png"
done
