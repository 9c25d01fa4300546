#!/usr/bin/env bash
# Plugin faults: a post-processor that crashes, hangs past the time limit, writes a
# non-finite number or one outside the machine's travel, fails mid-program, or writes a
# file past the size limit is reported with its name, and the run leaves no NC file (nor
# a temporary one), while the NC file of an earlier run stays as it was.
# usage: fault_test.sh <freeturn> <source dir> <fixture plugin dir>
set -u
freeturn=$1 src=$2 fixtures=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export FREETURN_PLUGIN_PATH=$fixtures
fail=0 passed=0
for case in "crash 3 crashed in blocks (SIGSEGV)" "hang 3 did not return from blocks within 2 s" \
            "nan 2 a number that is not finite" "travel 2 is outside the machine's range" \
            "error 2 the controller's block buffer is full" "bytes 2 would be larger than limits.max_file_mb"; do
  read -r fault code message <<< "$case"
  cat > "$tmp/faulty-$fault.yaml" <<YAML
name: faulty-$fault
plugin: faulty
axes:
  - {name: X, min: -100, max: 100, decimals: 6}
  - {name: Z, min: -50, max: 50, decimals: 6}
  - {name: C, decimals: 4}
faulty: {fault: $fault}
YAML
  sed -e "s|^machine: .*|machine: $tmp/faulty-$fault.yaml|" "$src/configs/jobs/oap_segment.yaml" > "$tmp/job-$fault.yaml"
  # The plugin's own bytes, not the CL file's (blocks reach the plugin only once the block
  # schedule's window is planned, after the CL rows are written).
  [[ $fault == bytes ]] && sed -i 's/^outputs: .*/outputs: {cl_csv: false}/' "$tmp/job-$fault.yaml" &&
    printf 'limits: {max_file_mb: 1}\n' >> "$tmp/job-$fault.yaml"
  out="$tmp/out-$fault"
  mkdir "$out"
  echo "an earlier program" > "$out/oap_segment.faulty-$fault.nc"
  # A 2 s limit for the hang; the others keep the default, however loaded the machine.
  timeout=60
  [[ $fault == hang ]] && timeout=2
  (cd "$src/configs/jobs" && FREETURN_PLUGIN_TIMEOUT=$timeout "$freeturn" run "$tmp/job-$fault.yaml" -o "$out" --quiet) 2> "$tmp/err"
  rc=$?
  ok=1
  [[ $rc == "$code" ]] || { echo "FAIL: $fault: exit code $rc, expected $code"; ok=0; }
  grep -q "post-processor 'faulty'" "$tmp/err" || { echo "FAIL: $fault: the message does not name the plugin"; ok=0; }
  grep -qF "$message" "$tmp/err" || { echo "FAIL: $fault: the message lacks '$message'"; ok=0; }
  [[ $(cat "$out/oap_segment.faulty-$fault.nc") == "an earlier program" ]] || { echo "FAIL: $fault: the earlier NC file changed"; ok=0; }
  left=$(ls "$out" | grep -v "^oap_segment.faulty-$fault.nc$")
  [[ -z "$left" ]] || { echo "FAIL: $fault: left $left"; ok=0; }
  if ((ok)); then passed=$((passed + 1)); else fail=1; sed 's/^/  /' "$tmp/err"; fi
done
echo "$passed passed, $((6 - passed)) failed"
exit $fail
