#!/usr/bin/env bash
# The denoising benchmark (docs/clean-images.md, "Benchmark"): for each scene of make_data.sh and
# 4, 16 and 64 spp, the relMSE of the raw and the denoised image against the 4096-spp reference,
# the gain, the sample-equivalent (the raw spp whose relMSE the denoised image equals, from the
# raw 512-spp render's relMSE and 1/spp scaling), the mean SSIM of the raw and the denoised
# image as displayed (imgdiff --ssim: sRGB, clamped) and the denoiser's time, as a Markdown table.
# Usage: bench/denoise/run.sh BUILD_DIR DATA_DIR   (BUILD_DIR configured with GLINT_BUILD_BENCH=ON)
set -euo pipefail
build=${1:?build dir}
data=${2:?data dir (bench/denoise/make_data.sh)}
eval=$build/bench/denoise_eval
ssim() {
    "$build/imgdiff" --ssim "$1" "$2" | awk '/^ssim/ { sub("mean=", "", $2); printf "%.3f", $2 }'
}
echo "| scene | spp | raw relMSE | denoised | gain | sample-equivalent | SSIM raw | SSIM denoised | mean / ref | denoise time |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for name in glass room lamps helmet bottle; do
    r512=$("$eval" "$data" "$name" 512 | sed -n 's/.*relMSE raw \([0-9.e-]*\) .*/\1/p')
    for spp in 4 16 64; do
        line=$("$eval" "$data" "$name" "$spp")
        raw=$(sed -n 's/.*relMSE raw \([0-9.e-]*\) .*/\1/p' <<<"$line")
        den=$(sed -n 's/.*denoised \([0-9.e-]*\) .*/\1/p' <<<"$line")
        gain=$(sed -n 's/.*gain \([0-9.]*x\).*/\1/p' <<<"$line")
        mean=$(sed -n 's/.*mean\/ref \([0-9.]*\).*/\1/p' <<<"$line")
        time=$(sed -n 's/.*time \([0-9.]* s\).*/\1/p' <<<"$line")
        equiv=$(awk -v r="$r512" -v d="$den" 'BEGIN { printf "%.0f", 512 * r / d }')
        ref=$data/${name}_ref.pfm
        sraw=$(ssim "$data/${name}_$spp.pfm" "$ref")
        sden=$(ssim "$data/${name}_$spp.denoised.pfm" "$ref")
        echo "| $name | $spp | $raw | $den | $gain | $equiv spp | $sraw | $sden | $mean | $time |"
    done
done
