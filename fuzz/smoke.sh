#!/usr/bin/env bash
# A short fuzz run: first every regression input once (each a crash found before, fixed
# since), then fuzzing from the checked-in corpus for N seconds. New inputs go to a
# scratch folder, never into the source tree. Fails on any crash, leak, timeout or
# out-of-memory report.
# usage: smoke.sh <fuzzer> <fuzz dir> <name> <seconds>
set -u
fuzzer=$1 dir=$2 name=$3 seconds=$4
if [[ ! -x "$fuzzer" ]]; then
  # scripts/test.sh builds every harness first; there a missing one is a broken build.
  [[ -n "${FREETURN_REQUIRE_FUZZ:-}" ]] && { echo "FAIL: $fuzzer was not built"; exit 1; }
  echo "$fuzzer not built (scripts/setup.sh fuzz): skipped"; exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
flags=(-rss_limit_mb=2048 -malloc_limit_mb=1024 -timeout=10 -print_final_stats=1)
if compgen -G "$dir/regressions/$name/*" > /dev/null; then
  "$fuzzer" "${flags[@]}" "$dir/regressions/$name"/* > regressions.log 2>&1 || {
    echo "FAIL: a regression input crashes again"; tail -40 regressions.log; exit 1; }
  echo "$(ls "$dir/regressions/$name" | wc -l) regression inputs pass"
fi
mkdir new
"$fuzzer" "${flags[@]}" -max_total_time="$seconds" new "$dir/corpus/$name" > fuzz.log 2>&1 || {
  echo "FAIL: fuzzing found a crash"; tail -60 fuzz.log; exit 1; }
grep -E "stat::number_of_executed_units|stat::peak_rss_mb" fuzz.log
echo "1 passed, 0 failed"
