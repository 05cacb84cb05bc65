# Shared by the bench scripts that time whole `glint --stats` runs (source it).
#
#   median                        reads numbers, one per line; prints their median
#   glint_runs RUNS OUT ARGS...   runs `ARGS...` (a glint command with -q --stats) RUNS times;
#                                 appends "parse build render write wall_s peak_MiB cpu_s" per
#                                 run to OUT and leaves the last run's --stats output in OUT.stats
#   glint_medians OUT             prints the table row of medians of OUT's runs (without cpu_s)
#   glint_cpu_median OUT          prints the median of OUT's cpu_s (user + system seconds)

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

glint_runs() {
    local runs=$1 out=$2
    shift 2
    local i rss wall cpu
    for ((i = 0; i < runs; i++)); do
        /usr/bin/time -v "$@" >"$out.stats" 2>"$out.time"
        rss=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$out.time")
        wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$out.time" |
            awk -F: '{print (NF == 3 ? $1 * 3600 + $2 * 60 + $3 : $1 * 60 + $2)}')
        cpu=$(awk -F': ' '/(User|System) time \(seconds\)/ {s += $2} END {print s}' "$out.time")
        awk -v rss="$rss" -v wall="$wall" -v cpu="$cpu" '
            /^Time/ {parse=$3; build=$6; render=$9; write=$12}
            END {print parse, build, render, write, wall, rss / 1024, cpu}' "$out.stats" >>"$out"
    done
}

glint_medians() {
    local row="" col
    for col in 1 2 3 4 5 6; do row="$row $(cut -d' ' -f$col "$1" | median)"; done
    # shellcheck disable=SC2086
    printf '%9.3f %9.3f %9.3f %9.3f %9.2f %12.0f' $row
}

glint_cpu_median() { cut -d' ' -f7 "$1" | median; }

glint_header() { printf '%9s %9s %9s %9s %9s %12s' parse_s build_s render_s write_s total_s peak_RSS_MiB; }
