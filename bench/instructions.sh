#!/usr/bin/env bash
# Instructions (callgrind, one thread) of whole renders: course scenes through the Whitted
# integrator, and the path tracer on the Cornell box, the light pass's caustic ball and a glTF
# model in the model mode. Instruction counts repeat exactly for the same binary and inputs,
# whatever else the machine does, so two builds compare to the instruction (a change to the
# code behind the renders, not to what they compute, should move them by well under 1%).
#
#   bench/instructions.sh build/glint            # prints: name  instructions
#   bench/instructions.sh OLD/glint NEW/glint    # and the ratio of the second to the first
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
shared=$root/../shared
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cases=(
    "course-scene6|$shared/scenes/cse167x/scene6.test"
    "course-scene7|$shared/scenes/cse167x/scene7.test"
    "path-cornell|$root/scenes/cornell.test --integrator path --spp 4 --size 160x160"
    "path-caustics|$root/bench/caustics/ball.test --spp 4"
    "path-media|$root/scenes/media.test --integrator path --spp 2 --size 120x90"
    "model-helmet|$shared/real-world/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf --size 96x72 --spp 4"
)
count() {  # BINARY ARGS...: the instructions of one render
    local bin=$1
    shift
    valgrind --tool=callgrind --callgrind-out-file="$tmp/out" "$bin" -q -t 1 "$@" \
        -o "$tmp/image.exr" 2>"$tmp/log" >/dev/null
    grep -m1 '^summary:' "$tmp/out" | awk '{print $2}'
}
printf '%-16s %16s' case "$(basename "$(dirname "$1")")/$(basename "$1")"
[ $# -gt 1 ] && printf ' %16s %8s' "$(basename "$(dirname "$2")")/$(basename "$2")" ratio
echo
for c in "${cases[@]}"; do
    name=${c%%|*}
    read -r -a args <<<"${c#*|}"
    [ -e "${args[0]}" ] || continue
    a=$(count "$1" "${args[@]}")
    printf '%-16s %16s' "$name" "$a"
    if [ $# -gt 1 ]; then
        b=$(count "$2" "${args[@]}")
        printf ' %16s %8.4f' "$b" "$(echo "$b / $a" | bc -l)"
    fi
    echo
done
