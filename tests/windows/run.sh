#!/bin/sh
# make test-windows BIN WIN_BIN WIN: Linux's frames of every preset in both
# desktop profiles (BIN/sky-render through OSMesa) into WIN/reference, then
# the Windows runner (WIN_BIN/sky-tests.exe) under Wine in an X server of
# its own (Xvfb), which compares sky-render.exe's frames against them. Wine
# keeps its prefix under WIN (its first start takes about 20 s) and prints
# nothing of its own (WINEDEBUG=-all). The runner's last line is
# "N passed, N failed"; the exit status is its.
set -eu
cd "$(dirname "$0")/../.."
bin=$1 win_bin=$2 win=$3
shift 3 # the rest: the runner's arguments (a test name's part)
ref=$win/reference
mkdir -p "$ref"
# the presets as sky-render --help lists them ("--preset a|b|c")
presets=$("$bin/sky-render" --help | sed -n 's/^ *--preset \([a-z|-]*\).*/\1/p' | tr '|' ' ')
[ -n "$presets" ] || { echo "test-windows: no presets in sky-render --help" >&2; exit 1; }
for p in $presets; do
    for gl in core compat; do
        "$bin/sky-render" --preset "$p" --gl "$gl" --out "$ref/$p-$gl.png"
    done
done
# (no Mono or Gecko: a fresh prefix would otherwise offer to download them)
export WINEDEBUG=-all WINEPREFIX="$PWD/$win/wineprefix" WINEDLLOVERRIDES="mscoree,mshtml="
export SKY_WINDOWS_REFERENCE="$ref" SKY_BIN="$(printf '%s' "$win_bin" | tr / '\\')"
export SKY_WINDOWS_PRESETS="$presets"
# (wineserver -w: every Wine process gone before the X server is, so none
# complains of its lost connection after the runner's last line)
xvfb-run -a -s '-screen 0 1280x720x24' sh -c 'wine "$0" "$@"; wineserver -w' "$win_bin/sky-tests.exe" "$@" 2>&1 |
    tr -d '\r' > "$win/test.log" || true
cat "$win/test.log"
tail -n 1 "$win/test.log" | grep -q '^[0-9]* passed, 0 failed'
