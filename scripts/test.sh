#!/usr/bin/env bash
# The test command: every check of the project, in order. Each stage is counted; the last
# line is "N passed, M failed" and the exit status is non-zero if any stage failed.
set -euo pipefail
cd "$(dirname "$0")/.."

passed=0
failed=0
failures=()

# Runs one stage, named $1, and counts it.
stage() {
    local name="$1"
    shift
    echo "==> $name"
    local start=$SECONDS
    if "$@"; then
        passed=$((passed + 1))
        echo "==> passed: $name ($((SECONDS - start)) s)"
    else
        failed=$((failed + 1))
        failures+=("$name")
        echo "==> FAILED: $name ($((SECONDS - start)) s)"
    fi
}

# The C tests live in c_tests/; a missing Makefile is a failure, not a skip.
c_tests() {
    if [ ! -f c_tests/Makefile ]; then
        echo "c_tests/Makefile is missing" >&2
        return 1
    fi
    make -C c_tests "$1"
}

stage "setup" bash scripts/setup.sh
stage "cargo fmt" cargo fmt --check
stage "cargo clippy" cargo clippy --all-targets -- -D warnings
stage "cargo build" cargo build --release
stage "cargo test" cargo test --profile release-tests
# The same tests in the debug profile (optimization level 1): debug assertions and integer
# overflow checks run there only.
stage "cargo test (debug)" cargo test
stage "header check" bash scripts/check-header.sh
stage "C tests" c_tests test
stage "Python tests" python3 tests/python/test_vs_triangle.py
stage "sanitized C tests" c_tests sanitize

if [ "$failed" -gt 0 ]; then
    echo "failed stages: ${failures[*]}"
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
