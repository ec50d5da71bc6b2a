#!/bin/sh
# Fetches the npm package d3-celestial (BSD-3; star data) into $1 with
# `npm pack` and unpacks it there.
set -e
dest=${1:?usage: fetch-d3celestial.sh DIR}
version=0.7.35
if [ -f "$dest/package/data/stars.8.json" ]; then exit 0; fi
command -v npm >/dev/null 2>&1 || { echo "fetch-d3celestial: npm is needed (apt-get install npm)" >&2; exit 1; }
mkdir -p "$dest"
cd "$dest"
npm pack "d3-celestial@$version" >/dev/null
tar xzf "d3-celestial-$version.tgz"
rm -f "d3-celestial-$version.tgz"
