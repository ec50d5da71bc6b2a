#!/bin/sh
# Regenerates the pictures of README.md and docs/ (docs/img) with sky-render
# and the programs (make screenshots); it edits no Markdown.
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
$r --size 640x360 --preset minimal --pitch 25 --gl compat --out $out/minimal-compat.png
$r --size 640x360 --preset moonlit --out $out/moonlit.png
# the planets (Night sky II): Venus and Jupiter half a degree apart in the
# evening twilight of 2023-03-01 over Munich
$r --size 640x400 --date 2023-03-01T17:45:00Z --lat 48.1 --lon 11.6 --features clouds,stars,starmap,planets,airglow,zodiacal --cover 0.1 --yaw 254 --pitch 15 --fov 40 --out $out/venus-jupiter.png
# the zodiacal light before dawn (35 N, 2023-10-15, new moon, the sun 18
# degrees down; without the planets, as Venus's glare stands in its
# cone); and one August night under Bortle 1, 4 and 8
$r --size 640x400 --date 2023-10-15T04:40:00Z --lat 35 --lon 0 --features stars,starmap,airglow,zodiacal --cover 0 --yaw 95 --pitch 22 --fov 100 --out $out/zodiacal-dawn.png
for b in 1 4 8; do
    $r --size 960x540 --date 2024-08-10T21:30:00Z --lat 45 --lon 10 --features stars,starmap,planets,airglow,zodiacal --cover 0 --bortle $b --yaw 180 --pitch 35 --fov 60 --out $out/bortle-$b.png
done
# the rainbow, the fogbow and a halo with parhelia (issue #44): the sun 20
# degrees up behind the viewer, showers and fog; the sun 29 up in cirrus
$r --size 640x360 --time 0.3275 --weather showers --features clouds,sun,weather,rainbow --yaw 288 --pitch 12 --fov 70 --out $out/rainbow.png
$r --size 640x360 --time 0.3275 --weather fog --features clouds,sun,weather,rainbow --yaw 288 --pitch 5 --fov 90 --out $out/fogbow.png
$r --size 640x360 --time 0.3625 --weather cirrus --features clouds,sun,weather,halo --yaw 118 --pitch 28 --fov 80 --out $out/halo.png
# the aurora (issue #44): Tromso on the moonless polar night of
# 2024-01-11 at Kp 6, looking north
$r --size 640x360 --features stars,starmap,airglow,aurora --kp 6 --date 2024-01-11T22:00:00Z --lat 69.65 --lon 18.96 --yaw 0 --pitch 20 --fov 90 --cover 0 --out $out/aurora.png
# the atmosphere paths (issue 6): a clear morning at 40 N on the 2026
# equinox, looking east toward the sun: day (sun 27 deg), sunrise (1.6
# deg) and civil twilight (-4 deg)
for a in gradient preetham rayleigh hillaire blend; do
    $r --size 320x180 --atmosphere $a --features sun --cover 0 --time 0.35 --yaw 100 --pitch 20 --fov 70 --out $out/atm-$a-day.png
    $r --size 320x180 --atmosphere $a --features sun --cover 0 --time 0.255 --yaw 91 --pitch 15 --fov 70 --out $out/atm-$a-sunrise.png
    $r --size 320x180 --atmosphere $a --features sun --cover 0 --time 0.235 --yaw 87 --pitch 15 --fov 70 --out $out/atm-$a-twilight.png
done
# the environment cube map as a cross (issue: the sky lights the scene):
# a late afternoon with clouds, 128 x 128 a face
$r --capture 128 --preset sunset --time 0.7 --out $out/env-cross.png
# the 8-bit output's colours (issue Look): a sunset toward the sun, 3
# degrees up, and Hillaire's twilight, 11 degrees down; the "before"
# pictures beside them were rendered by the code before that issue
mkdir -p $out/look
for a in gradient preetham rayleigh hillaire blend; do
    $r --size 320x180 --atmosphere $a --features sun --cover 0 --time 0.74 --yaw 268 --pitch 6 --fov 70 --out $out/look/$a-after.png
done
$r --size 320x180 --atmosphere hillaire --features sun --cover 0 --time 0.79 --yaw 268 --pitch 6 --fov 70 --out $out/look/hillaire-twilight-after.png
# one description, three planets (Hillaire's tables)
for p in earth hazy mars; do
    $r --size 320x180 --atmosphere hillaire --planet $p --features sun --cover 0 --time 0.35 --yaw 100 --pitch 20 --fov 70 --out $out/planet-$p-day.png
    $r --size 320x180 --atmosphere hillaire --planet $p --features sun --cover 0 --time 0.255 --yaw 91 --pitch 15 --fov 70 --out $out/planet-$p-sunrise.png
done
# a setting sun flattened by refraction (issue 11): 2026-03-20, 40 N 0 E,
# the centre 0.5 degree above the horizon, a 1.5-degree field on the sun
q=$($r --query --time 0.2505 | grep '"sun"')
alt=$(echo "$q" | sed 's/.*"sun": {"alt":\([-0-9.]*\).*/\1/')
az=$(echo "$q" | sed 's/.*"sun": {[^}]*"az":\([-0-9.]*\).*/\1/')
$r --size 240x240 --features sun --cover 0 --atmosphere hillaire --time 0.2505 --yaw "$az" --pitch "$alt" --fov 1.5 --out $out/sun-flattened.png
# the total solar eclipse of 2024-04-08 from near Nazas, Durango (25.29 N
# 104.14 W), first contact to last: a 2.5-degree field on the sun, the
# partial phases 8 stops down (as through a filter), totality at the
# automatic exposure; and the sky around at totality
eclipse() { # file UTC-time stops
    q=$($r --query --date "2024-04-08T$2Z" --lat 25.29 --lon -104.14 | grep '"sun"')
    alt=$(echo "$q" | sed 's/.*"sun": {"alt":\([-0-9.]*\).*/\1/')
    az=$(echo "$q" | sed 's/.*"sun": {[^}]*"az":\([-0-9.]*\).*/\1/')
    $r --size 160x160 --preset solar-eclipse --date "2024-04-08T$2Z" --yaw "$az" --pitch "$alt" --fov 2.5 \
        --exposure "$3" --out "$out/$1.png"
}
eclipse eclipse-1 16:59:30 -8
eclipse eclipse-2 17:40:00 -8
eclipse eclipse-3 18:12:00 -8
eclipse eclipse-4 18:17:20 0
eclipse eclipse-5 18:23:00 -8
eclipse eclipse-6 19:00:00 -8
eclipse eclipse-7 19:38:30 -8
$r --size 640x360 --preset solar-eclipse --out $out/eclipse-sky.png
$r --size 640x360 --preset solar-eclipse --date 2024-04-08T19:17:20Z --out $out/eclipse-sky-later.png
# moon close-ups: the camera on the moon, a 4-degree field, the disc at c_d = 2.5
moon() { # name date lat lon extra-features
    q=$($r --query --date "$2" --lat "$3" --lon "$4" | grep '"moon"')
    alt=$(echo "$q" | sed 's/.*"alt":\([-0-9.]*\).*/\1/')
    az=$(echo "$q" | sed 's/.*"az":\([-0-9.]*\).*/\1/')
    $r --size 240x240 --features moon,stars$5 --date "$2" --lat "$3" --lon "$4" --yaw "$az" --pitch "$alt" --fov 4 --out "$out/$1.png"
}
moon moon-crescent 2024-06-08T20:30:00Z 45 10 ""
moon moon-quarter 2024-06-14T20:00:00Z 45 10 ""
moon moon-full 2024-06-22T00:00:00Z -30 20 ""
moon moon-eclipse-2011 2011-06-15T20:11:31Z -20 57 ",eclipse"
# the windows need a display: under Xvfb when there is none
# what the dome's reduced image costs the eye (issue: Sharp at the same
# cost): 320x180 crops at 1:1 of 1280x720 frames. perf/: every preset at
# every pixel (left) and as drawn by default (right); dome-divisor: noon at
# every pixel, at its default 1/3, at 1/4 and at 1/5; sharp/: noon and
# sunset at every pixel, at 1/4 (the default before) and by default
frames=$(mktemp -d)
crop=build/bin/pngcrop
mkdir -p $out/perf $out/sharp
for p in minimal noon overcast sunset starry moonlit eclipse solar-eclipse; do
    $r --size 1280x720 --preset $p --dome-divisor 1 --out $frames/$p-1.png
    $r --size 1280x720 --preset $p --out $frames/$p.png
    $crop 480,120,320,180 1 $out/perf/$p.png $frames/$p-1.png $frames/$p.png
done
for d in 4 5; do $r --size 1280x720 --preset noon --dome-divisor $d --out $frames/noon-$d.png; done
$crop 700,150,320,180 1 $out/perf/dome-divisor.png $frames/noon-1.png $frames/noon.png $frames/noon-4.png $frames/noon-5.png
$r --size 1280x720 --preset sunset --dome-divisor 4 --out $frames/sunset-4.png
$crop 700,150,320,180 1 $out/sharp/noon.png $frames/noon-1.png $frames/noon-4.png $frames/noon.png
$crop 580,150,320,180 1 $out/sharp/sunset.png $frames/sunset-1.png $frames/sunset-4.png $frames/sunset.png
# the day's end (issue: Dusk and night): facing the sun at pitch 10 on the
# default date and place, the sun at 10, 4, 0, -3, -6, -9, -12, -15 and -18
# degrees (the time slider and the sun's azimuth there, from sky-render
# --query), on the default path and on Hillaire's
mkdir -p $out/dusk
dusk_times="10:0.71403:261.62 4:0.73631:266.87 0:0.75220:270.55 -3:0.76226:272.89 -6:0.77193:275.14
-9:0.78288:277.73 -12:0.79391:280.37 -15:0.80503:283.10 -18:0.81628:285.94"
for a in gradient hillaire; do
    strip=""
    for step in $dusk_times; do
        sun=${step%%:*} rest=${step#*:}
        $r --size 160x90 --atmosphere $a --time ${rest%%:*} --yaw ${rest#*:} --pitch 10 --fov 60 --out "$frames/$a$sun.png"
        strip="$strip $frames/$a$sun.png"
    done
    $crop 0,0,160,90 1 $out/dusk/$a.png $strip
done
# and two nights as the issue measures them (sky-bench's night rows): the
# full moon 67 degrees up, looking north, and a moonless sky, looking south
night="--size 320x180 --cover 0 --features clouds,sun,flicker,solar-eclipse,airglow,moon --pitch 30 --fov 60"
$r $night --date 2024-01-26T00:00:00Z --lat 45 --lon 0 --yaw 0 --out "$frames/fullmoon.png"
$r $night --date 2024-01-11T22:00:00Z --lat 45 --lon 10 --yaw 180 --out "$frames/moonless.png"
$crop 0,0,320,180 1 $out/dusk/nights.png "$frames/fullmoon.png" "$frames/moonless.png"
# the weather (issue: Weather): each state at noon looking south, 160x90;
# a change from fair to storm over 20 s, every 4 s; a night storm before
# and during a flash (seed 0's first strike, at 11.20 s); the cloud
# shadows on 10 km of ground at cover 0.3, 0.5 and 0.7 (north up)
mkdir -p $out/weather
wx="--size 320x180 --time 0.5 --pitch 15"
strip=""
for w in clear fair cirrus cloudy overcast; do $r $wx --weather $w --out "$frames/wx-$w.png"; strip="$strip $frames/wx-$w.png"; done
$crop 0,0,320,180 1 $out/weather/states-1.png $strip
strip=""
for w in rain showers storm fog snow; do $r $wx --weather $w --out "$frames/wx-$w.png"; strip="$strip $frames/wx-$w.png"; done
$crop 0,0,320,180 1 $out/weather/states-2.png $strip
strip=""
for t in 0 4 8 12 16 20; do
    $r --size 240x135 --time 0.5 --pitch 15 --weather fair --weather-to storm --weather-seconds 20 --seconds $t --out "$frames/change-$t.png"
    strip="$strip $frames/change-$t.png"
done
$crop 0,0,240,135 1 $out/weather/change.png $strip
for t in 11.0 11.21; do
    $r --size 320x180 --weather storm --time 0.95 --yaw 133 --pitch 10 --seconds $t --out "$frames/flash-$t.png"
done
$crop 0,0,320,180 1 $out/weather/flash.png "$frames/flash-11.0.png" "$frames/flash-11.21.png"
for c in 0.3 0.5 0.7; do $r --size 180x180 --time 0.5 --cover $c --out-shadow "$frames/shadow-$c.png"; done
$crop 0,0,180,180 1 $out/weather/shadows.png "$frames/shadow-0.3.png" "$frames/shadow-0.5.png" "$frames/shadow-0.7.png"
$r --size 640x360 --time 0.5 --pitch 15 --weather showers --out $out/weather.png
rm -r "$frames"
x=""
[ -n "${DISPLAY:-}" ] || x="xvfb-run -a -s '-screen 0 1280x720x24'"
eval $x build/bin/sky-demo --size 960x540 --frames 30 --screenshot $out/demo.png --preset starry \
    --date 2024-01-15T21:00:00Z --lat 45 --lon 10 --yaw 180 --pitch 30 >/dev/null
eval $x build/bin/sky-game --size 640x360 --frames 3 --screenshot $out/game-noon.png --time 0.45 >/dev/null
eval $x build/bin/sky-game --size 640x360 --frames 3 --screenshot $out/game-dusk.png --time 0.74 --sunset 0.8 >/dev/null
eval $x build/bin/sky-game --size 640x360 --frames 3 --screenshot $out/game-night.png --preset moonlit >/dev/null
eval $x build/bin/sky-game --size 640x360 --frames 3 --screenshot $out/game-night-moonless.png --preset starry >/dev/null
eval $x build/bin/sky-game --size 640x360 --frames 1 --screenshot $out/game-storm.png --time 0.5 --weather storm >/dev/null
eval $x build/bin/sky-game --size 640x360 --frames 1 --screenshot $out/game-shadows.png --weather cloudy --eye 300 --pitch -18 >/dev/null
eval $x build/bin/sky-game --size 640x360 --frames 1 --screenshot $out/game-shadows-60.png --weather cloudy --eye 300 --pitch -18 \
    --seconds 60 >/dev/null
eval $x build/bin/sky-game --size 640x360 --frames 1 --screenshot $out/game-flash.png --time 0.95 --weather storm --yaw 133 \
    --pitch 5 --seconds 11.21 >/dev/null
# the engine examples (make examples builds them): 7:12 in the morning,
# looking south
if [ -x build/examples/sky-sdl2 ] && [ -x build/examples/sky-osg ] && [ -x build/examples/sky-irrlicht ]; then
    mkdir -p $out/examples
    for e in sdl2 osg irrlicht; do
        eval $x build/examples/sky-$e --frames 3 --time 0.3 --screenshot $out/examples/$e.png >/dev/null
    done
else
    echo "screenshots: the examples are not built (make examples): their pictures left as they are"
fi
echo "screenshots: $(ls $out | tr '\n' ' ')"
# the browser build's page in headless Chromium, as make test-web sees it
# (when Emscripten and Chromium are installed: make web installs them)
if command -v emcc >/dev/null 2>&1 && command -v chromium-headless-shell >/dev/null 2>&1; then
    SKY_WEB_SHOT=$out/web.png make --no-print-directory test-web
fi
