#!/bin/sh
# make run: the sky in a window when there is a display; without one,
# sky-demo says so and renders build/sky.png headless (--out), or the file
# SKY_RUN_OUT names (the tests', so they leave make run's picture alone).
cd "$(dirname "$0")/.." || exit 1
exec build/bin/sky-demo --out "${SKY_RUN_OUT:-build/sky.png}" "$@"
