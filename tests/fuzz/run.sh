#!/bin/sh
# Runs each libFuzzer harness for SKY_FUZZ_SECONDS (default 20) from its
# seed corpus in tests/fuzz/corpus/NAME (new inputs go to a scratch
# directory, the seeds stay as they are). Prints one "ok"/"FAIL" line per
# harness with its executions, then "N passed, N failed".
cd "$(dirname "$0")/../.." || exit 1
dir=${SKY_FUZZ:-build/fuzz}
seconds=${SKY_FUZZ_SECONDS:-20}
passed=0
failed=0
for name in catalog png cli; do
    bin="$dir/fuzz_$name"
    [ -x "$bin" ] || continue
    work=$(mktemp -d)
    log="$work/log"
    ASAN_OPTIONS=detect_leaks=1 "$bin" -max_total_time="$seconds" -max_len=65536 -print_final_stats=1 \
        -artifact_prefix="$work/" "$work" "tests/fuzz/corpus/$name" > "$log" 2>&1
    rc=$?
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    if [ "$rc" -eq 0 ]; then
        echo "ok   fuzz_$name: ${execs:-?} executions in ${seconds} s, no crash"
        passed=$((passed + 1))
    else
        echo "FAIL fuzz_$name (exit $rc): a crash input was saved in $work"
        grep -E "ERROR|SUMMARY|runtime error" "$log" | head -5
        failed=$((failed + 1))
        continue # keep the artifact directory
    fi
    rm -rf "$work"
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
