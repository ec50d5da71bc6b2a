#!/bin/sh
# make bench-web: the browser's column of sky-bench's preset table. Serves
# build/web on 127.0.0.1, opens web/bench.html's page in Debian's headless
# Chromium (WebGL 1 through SwiftShader: no GPU, as llvmpipe here) and
# prints what the page measured: the one-texture quad, each preset and
# three.js's Sky (the npm package "three" at THREE_VERSION, as shipped),
# as ratios to the quad of the same round, medians over the rounds.
# three.js dropped WebGL 1 after r162, so r162 is pinned and its Sky runs in
# a WebGL 1 context like libsky's. BENCH_ROUNDS=N takes N rounds (5);
# BENCH_PRESETS=LIST times a list of presets instead, separated by ';',
# each with sky-render's options after it, URL-encoded
# ("starry;starry%20--features%20stars": a layer on its own).
set -e
cd "$(dirname "$0")/.."
THREE_VERSION=0.162.0
web=build/web
sh tools/fetch-npm.sh three "$THREE_VERSION" "$web/npm" package/build/three.module.js
rm -rf "$web/three" && cp -r "$web/npm/package" "$web/three"
port=$((18000 + $$ % 2000))
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$web" >/dev/null 2>&1 &
server=$!
trap 'kill $server 2>/dev/null' EXIT
for i in 1 2 3 4 5 6 7 8 9 10; do
    python3 -c "import urllib.request as u; u.urlopen('http://127.0.0.1:$port/bench.html')" 2>/dev/null && break
    sleep 0.2
done
log=$(mktemp)
shot=$(mktemp --suffix=.png)
# real time, not virtual: the page times its frames with performance.now;
# the screenshot (not kept) ends the run at the timeout
chromium-headless-shell --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
    --enable-logging=stderr --v=0 --window-size=1280,1500 --timeout=$((${BENCH_ROUNDS:-5} * 18000)) --screenshot="$shot" \
    "http://127.0.0.1:$port/bench.html?rounds=${BENCH_ROUNDS:-5}${BENCH_PRESETS:+&presets=$BENCH_PRESETS}" >"$log" 2>&1 || true
grep -o '"web-bench: round[^"]*"\|"stderr: [^"]*"' "$log" | sed 's/^"//; s/"$//'
json=$(grep -o '"web-bench: {.*}"' "$log" | sed 's/^"web-bench: //; s/"$//')
rm -f "$log" "$shot"
[ -n "$json" ] || { echo "bench-web: the page reported nothing" >&2; exit 1; }
echo
echo "$json" | python3 -c '
import json, sys
d = json.load(sys.stdin)
print("browser: %s, three.js r%s, %s, quad %.2f ms, medians of %d rounds of %d frames" %
      (d["renderer"], d["three"], d["size"], d["quad_ms"], d["rounds"], d["frames"]))
print()
print("| preset | browser ms | browser x baseline | rounds min-max |")
print("|---|---|---|---|")
for r in d["rows"]:
    print("| %s | %.2f | %.2f | %.2f-%.2f |" % (r["name"], r["ms"], r["ratio"], r["min"], r["max"]))
'
