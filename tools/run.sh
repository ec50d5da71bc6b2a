#!/bin/sh
# make run: the sky in a window when there is a display; without one,
# sky-demo says so and renders build/sky.png headless (--out).
cd "$(dirname "$0")/.." || exit 1
exec build/bin/sky-demo --out build/sky.png "$@"
