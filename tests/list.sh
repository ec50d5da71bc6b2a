#!/bin/sh
# tests/list.sh OUT FILE...: writes the test runner's list (the TESTS(X)
# macro tests/test_main.c expands) from the TEST(name) and SLOW_TEST(name)
# lines of the files, in their order, so that no list is kept by hand.
# X(name, 1) marks a slow test, which make check (--fast) leaves out.
out=$1
shift
tmp=$out.tmp.$$
{
    echo "/* written by tests/list.sh from the TEST lines of the runner's files */"
    echo "#define TESTS(X) \\"
    sed -n -e 's/^TEST(\([a-z0-9_]*\)).*/    X(\1, 0) \\/p' \
        -e 's/^SLOW_TEST(\([a-z0-9_]*\)).*/    X(\1, 1) \\/p' "$@"
    echo ""
} > "$tmp" && mv "$tmp" "$out"
