#!/usr/bin/env bash
# How long `make demo` takes on a fresh Debian 12 machine (issue 25: at most 3 minutes on two
# cores, apt included), measured in a chroot that has what a new machine of the project has and
# none of Glint's packages, from a fresh clone of a branch.
#
# Usage (as root; Debian's debootstrap, and overlayfs or enough disk for a copy of the chroot):
#   tools/fresh_demo_time.sh base ROOT
#       Makes ROOT (outside any git tree, e.g. /work/fresh-root/base): Debian 12 by debootstrap
#       (minbase), bookworm, -updates and -security, upgraded, with what a new machine has:
#       g++, cmake (with CTest), make, git, pkg-config, GoogleTest, GoogleMock, Google Benchmark,
#       clang-format, clang-tidy, cppcheck, clangd, bear, gdb, valgrind, heaptrack, python3,
#       Node.js, sudo, man-db; apt's package lists kept, its downloaded packages removed. About
#       3 minutes and 1.3 GB.
#   tools/fresh_demo_time.sh run ROOT [RUNS] [REV]
#       RUNS times (default 1): a copy of ROOT (an overlay on it, else cp -a) with /proc, /sys
#       and /dev mounted; a `git clone` of this repository into /root/glint there, checked out
#       at REV (a branch, tag or commit; default: the commit checked out here, not the working
#       tree); then `make demo` in it, timed. Prints each run's phases from the timestamps of
#       the lines make prints, and the medians:
#         apt        `make deps` for DEMO_DEPS: apt-get install (download, unpack, configure)
#         configure  cmake -S . -B build
#         build      cmake --build build --target glint
#         render     ./build/glint -o glint.png
#       and what else ran on the machine meanwhile (the build is timed by the wall clock: another
#       program using the cores slows it): the CPU seconds make demo used, and those the whole
#       machine used beyond them (from /proc/stat), with the load average before and after.
#       Each run's full output is kept in $FRESH_DEMO_LOGS (default /tmp/fresh-demo-logs).
#       Nothing is kept of the copy; ROOT is never changed.
set -euo pipefail

die() {
    echo "fresh_demo_time: $*" >&2
    exit 2
}
[ "$(id -u)" = 0 ] || die "needs root (debootstrap, chroot, mount)"
[ $# -ge 2 ] || die "usage: $0 base ROOT | run ROOT [RUNS] [REV]"
mode=$1
root=$(realpath -m "$2")

MIRROR=${MIRROR:-http://deb.debian.org/debian}
BASE_PACKAGES="g++ cmake make git pkg-config libgtest-dev libgmock-dev libbenchmark-dev
  clang-format clang-tidy cppcheck clangd bear gdb valgrind heaptrack python3 nodejs sudo man-db
  ca-certificates"

mounted=()
mount_system() {  # /proc, /sys and /dev of the host inside chroot $1
    mount -t proc proc "$1/proc" && mounted+=("$1/proc")
    mount --rbind /sys "$1/sys" && mount --make-rslave "$1/sys" && mounted+=("$1/sys")
    mount --rbind /dev "$1/dev" && mount --make-rslave "$1/dev" && mounted+=("$1/dev")
}
unmount_all() {
    local i
    for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
        umount -R "${mounted[i]}" 2>/dev/null || umount -lR "${mounted[i]}" || true
    done
    mounted=()
}
trap unmount_all EXIT

in_root() {  # runs a command in chroot $1 with a clean environment
    local r=$1
    shift
    chroot "$r" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
        PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin "$@"
}

if [ "$mode" = base ]; then
    command -v debootstrap >/dev/null || die "debootstrap is missing (apt-get install debootstrap)"
    [ ! -e "$root" ] || die "$root exists"
    case "$root" in "$(git rev-parse --show-toplevel 2>/dev/null || echo /nonexistent)"*)
        die "$root is inside this git tree";; esac
    debootstrap --variant=minbase bookworm "$root" "$MIRROR"
    cat >"$root/etc/apt/sources.list" <<EOF
deb $MIRROR bookworm main
deb $MIRROR bookworm-updates main
deb http://deb.debian.org/debian-security bookworm-security main
EOF
    cp /etc/resolv.conf "$root/etc/resolv.conf"
    mount_system "$root"
    in_root "$root" apt-get update -q
    in_root "$root" env DEBIAN_FRONTEND=noninteractive apt-get upgrade -y -q
    # shellcheck disable=SC2086
    in_root "$root" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y -q --no-install-recommends $BASE_PACKAGES
    in_root "$root" apt-get clean
    unmount_all
    echo "fresh_demo_time: $root is ready"
    exit 0
fi

[ "$mode" = run ] || die "unknown mode '$mode' (base or run)"
[ -x "$root/usr/bin/g++" ] || die "$root is not a chroot made by '$0 base'"
runs=${3:-1}
repo=$(git rev-parse --show-toplevel)
rev=$(git -C "$repo" rev-parse --verify "${4:-HEAD}^{commit}")
logs=${FRESH_DEMO_LOGS:-/tmp/fresh-demo-logs}
mkdir -p "$logs"
work=$(mktemp -d "$(dirname "$root")/fresh-demo.XXXXXX")
trap 'unmount_all; rm -rf "$work"' EXIT

# The CPU seconds the whole machine has been busy (every core; /proc/stat, in clock ticks).
busy() { awk -v hz="$(getconf CLK_TCK)" '/^cpu / {print ($2 + $3 + $4 + $7 + $8) / hz}' /proc/stat; }

# The seconds since $2 (from $EPOCHREALTIME) at which the first line matching $3 was printed,
# from a log whose lines begin with their time.
at() { awk -v re="$2" '$0 ~ re {print $1; exit}' "$1"; }

results=()
for ((run = 1; run <= runs; run++)); do
    copy=$work/root
    mkdir -p "$work/upper" "$work/work" "$copy"
    if mount -t overlay overlay \
        -o "lowerdir=$root,upperdir=$work/upper,workdir=$work/work" "$copy" 2>/dev/null; then
        mounted+=("$copy")
    else
        cp -a "$root/." "$copy/"
    fi
    mount_system "$copy"
    t=$(date +%s.%N)
    git clone -q --no-checkout "file://$repo" "$copy/root/glint"
    git -C "$copy/root/glint" checkout -q "$rev"
    commit=$(git -C "$copy/root/glint" rev-parse --short HEAD)
    clone=$(echo "$(date +%s.%N) - $t" | bc)
    log=$logs/run$run.log
    load0=$(cut -d' ' -f1-3 /proc/loadavg)
    busy0=$(busy)
    start=$EPOCHREALTIME
    set +e
    # `times` reports the CPU time of make and everything it ran (the last line of the log).
    in_root "$copy" /bin/bash -c 'cd /root/glint && make demo; s=$?; times; exit $s' 2>&1 |
        while IFS= read -r line; do
            printf '%8.2f %s\n' "$(echo "$EPOCHREALTIME - $start" | bc)" "$line"
        done >"$log"
    status=${PIPESTATUS[0]}
    set -e
    total=$(echo "$EPOCHREALTIME - $start" | bc)
    busy1=$(busy)
    load1=$(cut -d' ' -f1-3 /proc/loadavg)
    own=$(tail -1 "$log" | awk '{n = 0; for (i = 2; i <= 3; i++) {split($i, t, /[ms]/); n += t[1] * 60 + t[2]}; print n}')
    others=$(echo "$busy1 - $busy0 - $own" | bc)
    [ "$status" = 0 ] && [ -f "$copy/root/glint/glint.png" ] ||
        die "run $run: make demo failed (exit $status); see $log"
    t_cfg=$(at "$log" '^ *[0-9.]+ cmake -S ')
    t_build=$(at "$log" '^ *[0-9.]+ cmake --build ')
    t_render=$(at "$log" '^ *[0-9.]+ \./build/glint ')
    packages=$(awk '/glint: installing missing Debian packages:/ {print NF - 6; exit}' "$log")
    apt=$t_cfg
    configure=$(echo "$t_build - $t_cfg" | bc)
    build=$(echo "$t_render - $t_build" | bc)
    render=$(echo "$total - $t_render" | bc)
    printf 'run %d (%s): make demo %.1f s = apt %.1f (%s packages named) + configure %.1f + build %.1f + render %.1f; clone %.1f s\n' \
        "$run" "$commit" "$total" "$apt" "${packages:-0}" "$configure" "$build" "$render" "$clone"
    printf '  CPU: make demo %.1f s, other programs %.1f s (%.0f%% of %d cores); load %s -> %s\n' \
        "$own" "$others" "$(echo "100 * $others / ($total * $(nproc))" | bc -l)" "$(nproc)" \
        "$load0" "$load1"
    results+=("$total $apt $configure $build $render")
    unmount_all
    rm -rf "$work/upper" "$work/work" "$copy"
done

median() { sort -n | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
col() { for r in "${results[@]}"; do echo "$r" | cut -d' ' -f"$1"; done | median; }
printf 'median of %d: make demo %.1f s = apt %.1f + configure %.1f + build %.1f + render %.1f (%d cores)\n' \
    "$runs" "$(col 1)" "$(col 2)" "$(col 3)" "$(col 4)" "$(col 5)" "$(nproc)"
