#!/usr/bin/env bash
# The README's test command: set up (packages, ASan+UBSan build), then the whole suite
# through ctest, which ends with its summary line.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# The fuzz harnesses first (clang, libFuzzer): the suite's fuzz smoke runs use them.
"$root/scripts/setup.sh" fuzz
# Built just now, so a missing harness is a failure here, not a skipped smoke run.
export FREETURN_REQUIRE_FUZZ=1
"$root/scripts/setup.sh" asan
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
ctest --test-dir "$root/build/asan" --output-on-failure --parallel "$(nproc)"
