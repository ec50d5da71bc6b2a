#!/bin/sh
# Fetches an npm package at a pinned version into DIR with `npm pack` and
# unpacks it there (DIR/package/...), unless FILE (a path under DIR) is
# already there. The packages the assets and tables come from:
#   d3-celestial 0.7.35 (BSD-3): star data (textures/README.md)
#   astronomia 4.2.0 (MIT): the VSOP87 series (sky/planet_tables.c)
#   three 0.162.0 (MIT): three.js's Sky, timed beside libsky (make bench-web)
set -e
name=${1:?usage: fetch-npm.sh NAME VERSION DIR FILE}
version=${2:?usage: fetch-npm.sh NAME VERSION DIR FILE}
dest=${3:?usage: fetch-npm.sh NAME VERSION DIR FILE}
file=${4:?usage: fetch-npm.sh NAME VERSION DIR FILE}
if [ -f "$dest/$file" ]; then exit 0; fi
command -v npm >/dev/null 2>&1 || { echo "fetch-npm: npm is needed (apt-get install npm)" >&2; exit 1; }
mkdir -p "$dest"
cd "$dest"
npm pack --silent "$name@$version" >/dev/null
tar xzf "$name-$version.tgz"
rm -f "$name-$version.tgz"
