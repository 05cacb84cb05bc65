#!/usr/bin/env bash
# Weights on the denoising benchmark's held-out scenes (bench/denoise/make_data.sh's output):
# denoises each NAME_SPP.exr of DATA_DIR with WEIGHTS and with OIDN's own balanced weights
# (glint_unet_denoise, Glint's inference) and prints the relMSE of both against NAME_ref.pfm
# (bench/denoise/relmse.py), then per sample count their means, the ratio of the means and the
# geometric mean of the per-scene ratios (new / base: below 1, the new weights are better).
# Missing files are skipped.
# Usage: evaluate.sh WEIGHTS.tza [DATA_DIR [SPP...]]   (default /tmp/dnbench; 4 16 64)
# Environment: UNET (the glint_unet_denoise binary; default build/tools/ of this checkout),
#   BASE (the weights to compare with; default denoise-weights/oidn/rt_hdr_alb_nrm.tza),
#   THREADS (default 2), KEEP (a folder to keep the denoised PFMs in).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
weights=${1:?weights .tza}
data=${2:-/tmp/dnbench}
shift $(($# < 2 ? $# : 2))
spps=("$@")
[ ${#spps[@]} -gt 0 ] || spps=(4 16 64)
unet=${UNET:-$repo/build/tools/glint_unet_denoise}
base=${BASE:-$repo/denoise-weights/oidn/rt_hdr_alb_nrm.tza}
relmse=$repo/bench/denoise/relmse.py
py=$(command -v /usr/bin/python3 || command -v python3)
out=${KEEP:-$(mktemp -d)}
mkdir -p "$out"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$out"' EXIT
for f in "$unet" "$weights" "$base"; do
    [ -f "$f" ] || { echo "evaluate: $f is missing" >&2; exit 1; }
done

printf '%-8s %4s %12s %12s %7s\n' scene spp relMSE-base relMSE-new ratio
declare -A sum_base sum_new sum_log count
for spp in "${spps[@]}"; do
    sum_base[$spp]=0 sum_new[$spp]=0 sum_log[$spp]=0 count[$spp]=0
    for name in glass room lamps helmet bottle vase toycar chair cloth lamp; do
        exr=$data/${name}_$spp.exr ref=$data/${name}_ref.pfm
        if [ ! -f "$exr" ] || [ ! -f "$ref" ]; then continue; fi
        "$unet" "$base" "$exr" "$out/${name}_${spp}_base.pfm" --threads "${THREADS:-2}"
        "$unet" "$weights" "$exr" "$out/${name}_${spp}_new.pfm" --threads "${THREADS:-2}"
        b=$("$py" "$relmse" "$out/${name}_${spp}_base.pfm" "$ref" --all | cut -d" " -f2)
        n=$("$py" "$relmse" "$out/${name}_${spp}_new.pfm" "$ref" --all | cut -d" " -f2)
        printf '%-8s %4s %12s %12s %7.3f\n' "$name" "$spp" "$b" "$n" "$(echo "$n / $b" | bc -l)"
        sum_base[$spp]=$(echo "${sum_base[$spp]} + $b" | bc -l)
        sum_new[$spp]=$(echo "${sum_new[$spp]} + $n" | bc -l)
        sum_log[$spp]=$(echo "${sum_log[$spp]} + l($n / $b)" | bc -l)
        count[$spp]=$((count[$spp] + 1))
    done
done
for spp in "${spps[@]}"; do
    c=${count[$spp]}
    [ "$c" -gt 0 ] || continue
    printf '%-8s %4s %12.6f %12.6f %7.3f   geometric mean of the ratios %.3f (%d scenes)\n' \
        mean "$spp" "$(echo "${sum_base[$spp]} / $c" | bc -l)" \
        "$(echo "${sum_new[$spp]} / $c" | bc -l)" \
        "$(echo "${sum_new[$spp]} / ${sum_base[$spp]}" | bc -l)" \
        "$(echo "e(${sum_log[$spp]} / $c)" | bc -l)" "$c"
done
