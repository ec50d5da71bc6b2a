#!/bin/sh
# Fetches the npm package astronomia (MIT; it carries the VSOP87 series of
# Bretagnon & Francou 1988 as data files) into $1 with `npm pack` and
# unpacks it there.
set -e
dest=${1:?usage: fetch-astronomia.sh DIR}
version=4.2.0
if [ -f "$dest/package/data/vsop87Dmars.js" ]; then exit 0; fi
command -v npm >/dev/null 2>&1 || { echo "fetch-astronomia: npm is needed (apt-get install npm)" >&2; exit 1; }
mkdir -p "$dest"
cd "$dest"
npm pack "astronomia@$version" >/dev/null
tar xzf "astronomia-$version.tgz"
rm -f "astronomia-$version.tgz"
