#!/usr/bin/env bash
# Every example job in configs/jobs runs as it is; its NC programs match the golden files
# in tests/golden/<job>/ by ncdiff (values, not formatting); its report.json validates
# against docs/report.schema.json (tests/report/validate_report.py) and says PASS.
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
  report="$tmp/$job/$job.report.json"
  python3 "$src/tests/report/validate_report.py" "$src/docs/report.schema.json" "$report" > "$tmp/schema.txt"
  case $? in
    0) passed=$((passed + 1)) ;;
    77) ;;  # no python3-jsonschema: the schema check is skipped, the rest still runs
    *) echo "FAIL: $job's report.json:"; cat "$tmp/schema.txt"; failed=$((failed + 1)) ;;
  esac
  grep -q '<svg' "$tmp/$job/$job.report.html" || { echo "FAIL: $job report.html has no plot"; failed=$((failed + 1)); }
  # Every example runs with default checks and is safe to cut.
  python3 -c 'import json, sys; sys.exit(json.load(open(sys.argv[1]))["verdict"]["status"] != "PASS")' "$report" ||
    { echo "FAIL: $job is not PASS"; failed=$((failed + 1)); }
  # Inverse-time programs: the axes' velocities and accelerations read back from the NC
  # alone stay within the machine YAML's limits, and the report's cycle is their sum.
  machine=$(sed -n 's/^machine: *\([^ #]*\).*/\1/p' "$src/configs/jobs/$job.yaml")
  yaml=$(ls "$src"/postprocessors/*/machines/"$machine".yaml)
  plugin=$(sed -n 's/^plugin: *\([^ #]*\).*/\1/p' "$yaml")
  main="$tmp/$job/$job.$machine.nc"
  if [[ "$plugin" == moore || "$plugin" == iso ]] && grep -q G93 "$main" "$tmp/$job"/*.nc; then
    cycle=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["passes"][-1]["cycle_time_s"])' "$report")
    if python3 "$src/tests/jobs/nc_dynamics.py" "$main" "$yaml" "$plugin" --cycle "$cycle" > "$tmp/dyn.txt"; then
      passed=$((passed + 1))
    else
      echo "FAIL: $job's program exceeds its machine or its cycle time:"; cat "$tmp/dyn.txt"; failed=$((failed + 1))
    fi
  fi
done
echo "$passed passed, $failed failed"
[[ $failed == 0 ]]
