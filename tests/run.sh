#!/bin/sh
# make test: the test runner, then the same runner built with AddressSanitizer
# and UndefinedBehaviorSanitizer, then (where clang's libFuzzer links) a
# short run of each fuzzing harness; the last line adds them all up as
# "N passed, N failed" (", N skipped" after it when a test could not run).
# Runs from the repository root so relative paths in tests resolve.
cd "$(dirname "$0")/.." || exit 1
bin=${SKY_BIN:-build/bin}
asan=${SKY_ASAN:-build/asan}
out=$(mktemp)
filter=${1:-} # optional: only tests whose name contains it

# the three counts of a runner's last line ("N passed, N failed", with
# ", N skipped" or without: then 0 skipped), or none
counts() {
    tail -n 1 "$1" | sed -n -e 's/^\([0-9]*\) passed, \([0-9]*\) failed$/\1 \2 0/p' \
        -e 's/^\([0-9]*\) passed, \([0-9]*\) failed, \([0-9]*\) skipped$/\1 \2 \3/p'
}

"$bin/sky-tests" $filter | tee "$out"
set -- $(counts "$out")
passed=${1:-0}
failed=${2:-1} # no summary line: the runner died
skipped=${3:-0}

if [ -x "$asan/sky-tests" ]; then
    echo "== the same tests under AddressSanitizer + UndefinedBehaviorSanitizer =="
    # leaks are LeakSanitizer's job (api_leaks_1000_cycles, which runs
    # sky-leaks with detect_leaks=1 and Mesa's own allocations suppressed);
    # here memory errors and undefined behaviour
    SKY_LEAKS= ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 "$asan/sky-tests" $filter > "$out" 2>&1
    asan_status=$?
    grep -E "^(ok|FAIL|skip) |runtime error|ERROR: AddressSanitizer" "$out" | sed 's/^/  asan: /'
    summary=$(counts "$out")
    if [ -z "$summary" ]; then
        tail -n 20 "$out" # a sanitizer abort leaves no summary line
        failed=$((failed + 1))
    else
        set -- $summary
        passed=$((passed + $1))
        failed=$((failed + $2))
        skipped=$((skipped + $3))
        if [ "$asan_status" -ne 0 ] && [ "$2" -eq 0 ]; then failed=$((failed + 1)); fi
    fi
fi
fuzz=${SKY_FUZZ:-}
if [ -z "$filter" ] && [ -n "$fuzz" ] && [ -d "$fuzz" ]; then
    echo "== libFuzzer harnesses, ${SKY_FUZZ_SECONDS:-20} s each =="
    SKY_FUZZ="$fuzz" sh tests/fuzz/run.sh > "$out" 2>&1
    sed '$d' "$out" | sed 's/^/  fuzz: /'
    summary=$(counts "$out")
    if [ -z "$summary" ]; then
        failed=$((failed + 1))
    else
        set -- $summary
        passed=$((passed + $1))
        failed=$((failed + $2))
    fi
fi
rm -f "$out"
if [ "$skipped" -gt 0 ]; then
    echo "$passed passed, $failed failed, $skipped skipped"
else
    echo "$passed passed, $failed failed"
fi
[ "$failed" -eq 0 ]
