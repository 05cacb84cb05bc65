#!/usr/bin/env bash
# The denoising benchmark (docs/clean-images.md, "Benchmark"): for each scene of make_data.sh at
# 4, 16 and 64 spp, the relMSE against the 4096-spp reference of the raw image, of Glint's
# non-local-means filter (nlm) and of Open Image Denoise's network at its three qualities (oidn
# fast, balanced, high), and the sample-equivalent of the default (balanced): the raw spp whose
# relMSE it equals, read off the raw renders' own curve (4 to 512 spp, log-log between them;
# ">512" past the last). Then, at 16 spp, what each denoiser keeps of the reference's detail
# (metrics.h, detailKept: 1 all of it, 0 none), the relMSE without the worst 0.1% of pixels, the
# mean against the reference's and the time (320x240, 2 threads).
# Markdown tables on standard output.
# Usage: bench/denoise/run.sh BUILD_DIR DATA_DIR [NAME...]
#        (BUILD_DIR configured with GLINT_BUILD_BENCH=ON; DATA_DIR from make_data.sh)
set -euo pipefail
build=${1:?build dir}
data=${2:?data dir (bench/denoise/make_data.sh)}
shift 2
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(glass room lamps helmet bottle vase toycar chair cloth lamp caustic)
eval=$build/bench/denoise_eval
field() { sed -n "s|.*$1 \([0-9.e-]*\).*|\1|p" <<<"$2"; }
declare -A line
for name in "${names[@]}"; do
    for spp in 4 16 64 128 512; do
        line[$name,$spp,raw]=$("$eval" "$data" "$name" "$spp" out=none)
    done
    for spp in 4 16 64; do
        line[$name,$spp,nlm]=${line[$name,$spp,raw]}
        [ "$spp" = 16 ] && line[$name,$spp,nlm]=$("$eval" "$data" "$name" "$spp" runs=3)
        for q in fast balanced high; do
            runs=1; [ "$spp" = 16 ] && runs=3
            line[$name,$spp,$q]=$("$eval" "$data" "$name" "$spp" denoiser=oidn quality=$q runs=$runs)
        done
    done
done

raw() { field 'relMSE raw' "${line[$1,$2,raw]}"; }
den() { field '  denoised' "$(sed 's/trimmed.*//' <<<"${line[$1,$2,$3]}")"; }
echo "| scene | spp | raw | nlm | oidn fast | oidn balanced | oidn high | balanced = raw at | raw 128 | raw 512 |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for name in "${names[@]}"; do
    curve=""
    for s in 4 16 64 128 512; do curve="$curve $s $(raw "$name" $s)"; done
    for spp in 4 16 64; do
        b=$(den "$name" "$spp" balanced)
        equiv=$(awk -v d="$b" -v c="$curve" 'BEGIN {
            n = split(c, a, " ");
            for (i = 1; i + 3 <= n; i += 2) {
                s0 = a[i]; r0 = a[i + 1]; s1 = a[i + 2]; r1 = a[i + 3];
                if (d <= r0 && d >= r1) {
                    t = log(r0 / d) / log(r0 / r1);
                    printf "%.0f spp", exp(log(s0) + t * log(s1 / s0)); exit
                }
            }
            if (d > a[2]) printf "<4 spp"; else printf ">512 spp"
        }')
        echo "| $name | $spp | $(raw "$name" "$spp") | $(den "$name" "$spp" nlm) | $(den "$name" "$spp" fast) |" \
             "**$b** | $(den "$name" "$spp" high) | $equiv | $(raw "$name" 128) | $(raw "$name" 512) |"
    done
done

echo
echo "At 16 spp:"
echo
echo "| scene | detail kept: raw | nlm | oidn balanced | oidn high | trimmed relMSE: nlm | oidn balanced | mean / ref: nlm | oidn balanced | time: nlm | fast | balanced | high |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for name in "${names[@]}"; do
    n=${line[$name,16,nlm]} b=${line[$name,16,balanced]} h=${line[$name,16,high]}
    f=${line[$name,16,fast]}
    echo "| $name | $(field 'detail raw' "$n") | $(field 'detail raw [0-9.]*  denoised' "$n") |" \
         "$(field 'detail raw [0-9.]*  denoised' "$b") | $(field 'detail raw [0-9.]*  denoised' "$h") |" \
         "$(field 'trimmed raw [0-9.]*  denoised' "$n") | $(field 'trimmed raw [0-9.]*  denoised' "$b") |" \
         "$(field 'mean/ref' "$n") | $(field 'mean/ref' "$b") | $(field time "$n") s |" \
         "$(field time "$f") s | $(field time "$b") s | $(field time "$h") s |"
done
