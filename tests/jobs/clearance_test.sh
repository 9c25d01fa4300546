#!/usr/bin/env bash
# The way in and out of a cut never touches the part: a convex sphere (its vertex the
# highest point, above where the spiral starts) is cut on a Moore and an ISO machine, and
# every move of the written program, approach and retract included, is checked against
# the sphere by tests/jobs/nc_clearance.py, which shares no code with freeturn. (The
# retract used to return to `retract` above the first point, 0.29 mm inside this part.)
# usage: clearance_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
for machine in moore-nanotech-250upl iso-lathe-xzc; do
  cat > "$tmp/convex.yaml" <<YAML
name: convex
aperture: {outer_radius: 10.0}
surface: {type: even_asphere, radius: -40.0, conic: 0}
tool: {nose_radius: 0.5}
strategy:
  mode: spiral
  spiral: planar
  pitch: 0.2
  points: {chord: {tolerance: 0.001, max_angle_deg: 5}}
cutting: {spindle_rpm: 100}
machine: $machine
YAML
  rm -rf "$tmp/out"
  if ! "$freeturn" run "$tmp/convex.yaml" -o "$tmp/out" --quiet; then
    echo "FAIL: $machine: the run failed"; fail=1; continue
  fi
  if python3 "$src/tests/jobs/nc_clearance.py" "$tmp/out/convex.$machine.nc" 40 0.5 > "$tmp/clear.txt"; then
    echo "$machine: $(cat "$tmp/clear.txt")"
  else
    echo "FAIL: $machine: $(cat "$tmp/clear.txt")"; fail=1
  fi
done
exit $fail
