#!/bin/sh
# Fetches the Debian 12 source packages of zlib and libpng (apt-get source, from the same
# Debian archive as the binary packages) into DIR, unpacked: the web build compiles them with
# Emscripten, whose own ports would download them from elsewhere. zlib is the version of the
# installed zlib1g, so that PNG files deflate byte for byte as the native build's do.
#
#   web/tools/debian-sources.sh DIR
#
# apt-get runs on a private configuration in DIR/apt (a deb-src list of the system's Debian
# archive): the system's apt sources are not touched. Nothing is fetched when DIR has them.
set -eu
dir=${1:?usage: debian-sources.sh DIR}
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
if [ -f "$dir/zlib/zlib.h" ] && [ -f "$dir/libpng/png.h" ]; then exit 0; fi

apt="$dir/apt"
mkdir -p "$apt/lists/partial" "$apt/cache/archives/partial" "$dir/fetch"
keyring=/usr/share/keyrings/debian-archive-keyring.gpg
cat > "$apt/sources.list" <<LIST
deb-src [signed-by=$keyring] http://deb.debian.org/debian bookworm main
deb-src [signed-by=$keyring] http://deb.debian.org/debian bookworm-updates main
deb-src [signed-by=$keyring] http://deb.debian.org/debian-security bookworm-security main
LIST
opts="-o Dir::Etc::SourceList=$apt/sources.list -o Dir::Etc::SourceParts=/dev/null
      -o Dir::State::Lists=$apt/lists -o Dir::Cache=$apt/cache -o APT::Sandbox::User=root -q"
# shellcheck disable=SC2086
apt-get $opts update >/dev/null

# Installed versions first (the binary packages the native build links), then any other.
versions() {  # PACKAGE BINARY
    dpkg-query -W -f='${source:Version}\n' "$2" 2>/dev/null || true
    # shellcheck disable=SC2086
    apt-cache $opts showsrc "$1" | sed -n 's/^Version: //p'
}
fetch() {  # PACKAGE BINARY NAME
    for v in $(versions "$1" "$2"); do
        # shellcheck disable=SC2086
        if (cd "$dir/fetch" && apt-get $opts source "$1=$v" >/dev/null 2>&1); then
            rm -rf "${dir:?}/$3"
            mv "$dir/fetch/$(cd "$dir/fetch" && ls -d "$1"-*/ | head -1)" "$dir/$3"
            echo "$1 $v" > "$dir/$3/DEBIAN_SOURCE_VERSION"
            echo "glint: Debian source $1 $v in $dir/$3"
            rm -rf "$dir/fetch"/*
            return 0
        fi
    done
    echo "glint: error: cannot fetch the Debian source package $1" >&2
    return 1
}
fetch zlib zlib1g zlib
fetch libpng1.6 libpng16-16 libpng
