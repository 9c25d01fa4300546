#!/usr/bin/env bash
# Every example job in configs/jobs runs as it is; its NC programs match the golden files
# in tests/golden/<job>/ by ncdiff (values, not formatting); its report has the figures.
# Golden files change only on purpose: regenerate with
#   freeturn run configs/jobs/<job>.yaml -o tests/golden/<job> --quiet   (then keep the .nc)
# usage: examples_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0 failed=0
for golden_dir in "$src"/tests/golden/*/; do
  job=$(basename "$golden_dir")
  if ! "$freeturn" run "$src/configs/jobs/$job.yaml" -o "$tmp/$job" --quiet 2> "$tmp/$job.err"; then
    echo "FAIL: $job did not run:"; cat "$tmp/$job.err"; failed=$((failed + 1)); continue
  fi
  for golden in "$golden_dir"*.nc; do
    name=$(basename "$golden")
    if [[ ! -f "$tmp/$job/$name" ]]; then
      echo "FAIL: $job wrote no $name"; failed=$((failed + 1)); continue
    fi
    if "$freeturn" ncdiff "$golden" "$tmp/$job/$name" --tolerance 1e-9 > "$tmp/diff.txt"; then
      passed=$((passed + 1))
    else
      echo "FAIL: $job/$name differs from its golden file:"; cat "$tmp/diff.txt"; failed=$((failed + 1))
    fi
  done
  # No NC file beyond the golden ones (a new child file would be a change too).
  for made in "$tmp/$job"/*.nc; do
    [[ -f "$golden_dir$(basename "$made")" ]] || { echo "FAIL: $job wrote an unexpected $(basename "$made")"; failed=$((failed + 1)); }
  done
  for field in '"points": ' '"chord_error_mm": {"max": ' '"cycle_time_s": ' '"max_rpm": ' '"checks": {'; do
    grep -qF "$field" "$tmp/$job/report.json" || { echo "FAIL: $job report.json lacks $field"; failed=$((failed + 1)); }
  done
  grep -q '<svg' "$tmp/$job/report.html" || { echo "FAIL: $job report.html has no plot"; failed=$((failed + 1)); }
done
echo "$passed passed, $failed failed"
[[ $failed == 0 ]]
