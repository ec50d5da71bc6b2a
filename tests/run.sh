#!/bin/sh
# make test: runs the test runner (which ends with "N passed, N failed").
# Runs from the repository root so relative paths in tests resolve.
cd "$(dirname "$0")/.." || exit 1
exec "${SKY_BIN:-build/bin}/sky-tests" "$@"
