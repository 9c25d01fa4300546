#!/usr/bin/env bash
# Resource limits: a job over limits.max_points is refused before any planning when the
# bound says so (120 points per turn at the 3° cap × 100 turns > 1000), or as soon as
# the count passes it (12 000 allowed, 12 001 made); a CL file over limits.max_file_mb is
# refused when the job is read (at least 64 bytes a point); an NC program when the machine
# is known (12 000 points of at least 27 bytes on an X-Z-C lathe: 0.309 MB > 0.2), or while
# it is written (0.4 MB: the estimate passes, the 0.6 MB program does not). Each run exits
# 2 with the limit's name and writes nothing.
# usage: limits_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0 passed=0
for case in "max_points 1000 asks for at least 12000 points" \
            "max_points 12000 limits.max_points" \
            "max_file_mb 0.1 a CL file of at least" \
            "max_file_mb 0.2 an NC program of at least 0.309 MB" \
            "max_file_mb 0.4 would be larger than limits.max_file_mb"; do
  read -r key value message <<< "$case"
  limit="$key: $value"
  cp "$src/configs/jobs/oap_segment.yaml" "$tmp/job.yaml"
  # The NC program's own limit is met as it is written: without the CL file, whose size
  # the reader bounds before planning.
  [[ "$key" == max_file_mb && "$value" != 0.1 ]] && sed -i 's/^outputs: .*/outputs: {cl_csv: false}/' "$tmp/job.yaml"
  printf 'limits: {%s}\n' "$limit" >> "$tmp/job.yaml"
  rm -rf "$tmp/out"
  start=$(date +%s%N)
  (cd "$src/configs/jobs" && "$freeturn" run "$tmp/job.yaml" -o "$tmp/out" --quiet) 2> "$tmp/err"
  rc=$?
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  ok=1
  [[ $rc == 2 ]] || { echo "FAIL: $limit: exit code $rc, expected 2"; ok=0; }
  grep -qF "$message" "$tmp/err" || { echo "FAIL: $limit: the message lacks '$message'"; ok=0; }
  [[ -z "$(ls -A "$tmp/out" 2> /dev/null)" ]] || { echo "FAIL: $limit: wrote $(ls "$tmp/out")"; ok=0; }
  echo "$limit: refused after $ms ms"
  if ((ok)); then passed=$((passed + 1)); else fail=1; sed 's/^/  /' "$tmp/err"; fi
done
echo "$passed passed, $((5 - passed)) failed"
exit $fail
