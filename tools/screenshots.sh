#!/bin/sh
# Regenerates the README's screenshots with sky-render (make screenshots).
set -e
cd "$(dirname "$0")/.."
out=docs/img
mkdir -p "$out"
r=build/bin/sky-render
$r --size 640x360 --preset noon --pitch 25 --out $out/day.png
$r --size 640x360 --preset sunset --yaw 270 --pitch 8 --out $out/sunset.png
$r --size 640x360 --preset overcast --pitch 20 --out $out/overcast.png
$r --size 640x360 --preset starry --date 2024-01-15T21:00:00Z --lat 45 --lon 10 --yaw 180 --pitch 30 --fov 75 --out $out/night.png
$r --size 640x360 --preset starry --cover 0 --date 2024-08-10T21:00:00Z --lat 45 --lon 10 --yaw 180 --pitch 30 --fov 90 --out $out/milkyway.png
$r --size 640x360 --preset minimal --time 0.02 --pitch 35 --out $out/flicker.png
$r --size 360x360 --fisheye --time 0.3 --cover 0.5 --out $out/fisheye.png
$r --size 640x360 --preset minimal --pitch 25 --out $out/minimal-compat.png
echo "screenshots: $(ls $out | tr '\n' ' ')"
