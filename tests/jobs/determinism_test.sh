#!/usr/bin/env bash
# Determinism: the same job gives byte-identical NC programs, CL file, residual grid and
# report on repeated runs and on 1, 2 and 8 threads (docs/robustness.md says why).
# usage: determinism_test.sh <freeturn> <source dir> <job>...
set -u
freeturn=$1 src=$2
shift 2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0 compared=0
for job in "$@"; do
  for run in t1 t2 t8 t8again; do
    threads=${run#t}; threads=${threads%again}
    "$freeturn" run "$src/configs/jobs/$job.yaml" -o "$tmp/$job.$run" --quiet --simulate --threads "$threads" \
      || { echo "FAIL: $job on $threads threads did not run"; fail=1; continue 2; }
  done
  for f in "$tmp/$job.t1"/*; do
    name=$(basename "$f")
    case "$name" in *.nc|*.csv|*.report.json|*.report.html|*.ply|*.obj|*.vtk) ;; *) continue ;; esac
    for run in t2 t8 t8again; do
      compared=$((compared + 1))
      cmp -s "$f" "$tmp/$job.$run/$name" || { echo "FAIL: $job: $name differs between 1 thread and $run"; fail=1; }
    done
  done
done
echo "$compared comparisons, byte for byte"
[[ $fail == 0 ]] && echo "1 passed, 0 failed"
exit $fail
