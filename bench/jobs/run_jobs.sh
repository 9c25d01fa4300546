#!/usr/bin/env bash
# Whole jobs end to end: points per second and peak memory on 1 and 2 threads, and whether
# the programs are the same bytes on both (docs/path.md, "Whole jobs").
#
# usage: bench/jobs/run_jobs.sh [FREETURN] [JOB.yaml ...]
#   FREETURN  the freeturn binary (default: build/release/bin/freeturn, scripts/setup.sh release)
#   JOB.yaml  jobs to run (default: the demo, bench/jobs/compound_eye_2M.yaml and
#             bench/jobs/compound_eye_20M.yaml)
# Environment: THREADS (default "1 2"), RUNS (runs per job and thread count, default 1; the
# median wall time is printed).
#
# Each run is timed by /usr/bin/time -v (wall clock, peak resident set). The points are
# the blocks that carry an X or C word in the programs written (the path's points, and the
# few blocks of the approach and the retract). The machine is often shared: compare builds as ratios taken in one
# session, alternating them, not against figures from another day.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
freeturn=${1:-$root/build/release/bin/freeturn}
shift || true
jobs=("$@")
[[ ${#jobs[@]} -gt 0 ]] || jobs=("$root/configs/jobs/compound_eye.yaml" "$here/compound_eye_2M.yaml" "$here/compound_eye_20M.yaml")
threads=${THREADS:-1 2}
runs=${RUNS:-1}
[[ -x $freeturn ]] && freeturn=$(cd "$(dirname "$freeturn")" && pwd)/$(basename "$freeturn")
[[ -x $freeturn ]] || { echo "no freeturn binary at $freeturn (build it: scripts/setup.sh release)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "/usr/bin/time is needed (Debian package: time)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "freeturn: $freeturn"
echo "cores: $(nproc), $(date -u +%Y-%m-%d)"
echo
echo "| job | threads | points | wall (s) | points/s | peak RSS (MB) | programs |"
echo "|---|---|---|---|---|---|---|"
for job in "${jobs[@]}"; do
  [[ -f $job ]] || { echo "no job file $job" >&2; exit 2; }
  job=$(cd "$(dirname "$job")" && pwd)/$(basename "$job")
  name=$(basename "$job" .yaml)
  first=""
  for n in $threads; do
    walls=()
    for ((r = 0; r < runs; ++r)); do
      out="$tmp/$name-$n"
      rm -rf "$out"
      (cd "$(dirname "$job")" && /usr/bin/time -v -o "$tmp/time" "$freeturn" run "$job" -o "$out" \
        --threads "$n" --quiet) > /dev/null 2> "$tmp/err" || {
        status=$?
        # 1: the run wrote its programs and reported a check (a verdict, not a failure here).
        [[ $status -eq 1 ]] || { echo "$name: freeturn exited $status:" >&2; cat "$tmp/err" >&2; exit 1; }
      }
      wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0;
                          for (i = 1; i <= n; ++i) s = s * 60 + p[i]; print s}' "$tmp/time")
      rss=$(awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$tmp/time")
      walls+=("$wall")
    done
    wall=$(printf '%s\n' "${walls[@]}" | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}')
    points=$(cat "$out"/*.nc | grep -v '^ *(' | grep -c '[XC] *-\?[0-9.]' || true)
    rate=$(awk -v p="$points" -v w="$wall" 'BEGIN {r = 0; if (w > 0) r = p / w / 1000; printf "%.1f k", r}')
    same="-"
    if [[ -z $first ]]; then
      first=$out.kept
      rm -rf "$first"
      cp -r "$out" "$first"
    else
      same="same bytes as $(basename "${first%.kept}" | sed "s/^$name-//") thread(s)"
      for f in "$first"/*.nc; do
        cmp -s "$f" "$out/$(basename "$f")" || same="DIFFERENT from $(basename "${first%.kept}" | sed "s/^$name-//") thread(s)"
      done
    fi
    echo "| $name | $n | $points | $wall | $rate | $rss | $same |"
  done
done
