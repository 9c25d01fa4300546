#!/usr/bin/env bash
# A spiral at one constant spindle speed stops after its last block: a tilted sphere on a
# lathe whose C may accelerate 2 600 °/s², cut edge to centre and centre to edge, with
# linear motion and under PVT. Coming to
# rest over the last block asks C for ω²/Δθ, as starting from rest over the first does.
# Read back from the NC alone (tests/jobs/nc_dynamics.py: the last block ends at rest),
# every axis stays within the machine. Before the stop was judged, the edge-to-centre
# program asked C for 40 187 °/s²; once it was, its last block (0.195°, what the path's
# last step left) set the speed, 3.71 rpm. The path's last steps are now laid out so that
# the last block is a whole step, the 3.07° cap here as the first block is: the stop then
# allows what the start does, ω = √(0.98 · 2600 · 3.07) °/s = 14.741 rpm, both ways. Equal
# angles and equal arcs lay out their last steps alike (at the end of this file).
# usage: constant_speed_stop_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
cat > "$tmp/slow-c-lathe.yaml" <<'YAML'
name: slow-c-lathe
plugin: moore
axes:
  - {name: X, sign: 1, min: -75, max: 75, decimals: 6, max_velocity: 0.25, max_acceleration: 5}
  - {name: Z, sign: 1, min: -75, max: 75, decimals: 6, max_velocity: 5, max_acceleration: 400}
  - {name: C, sign: 1, decimals: 5, max_velocity: 260, max_acceleration: 2600}
c_axis: wrapped
interpolation: linear
max_block_rate: 1000
moore:
  header: "G71 G01 G18 G40 G63 G90 G94 G54\nT0101\nG53 Z-180.\nM80\nG09 C0.0\nG92 C0.0"
  footer: "G53 Z-180.\nM79\nG52\nT0000\nM30"
  spindle: M03
  retract: 1.0
  approach_feed: 12
  child_blocks: 0
YAML
fail=0
for direction in edge_to_centre centre_to_edge; do
  cat > "$tmp/tilted.yaml" <<YAML
name: tilted
aperture: {outer_radius: 2.7}
surface: {type: sphere, radius: -112.5, decenter: {x: 5.4}}
tool: {nose_radius: 0.05, included_angle_deg: 90}
strategy:
  mode: spiral
  spiral: space
  base_surface: {fit: minimax}
  pitch: 0.027
  points: {chord: {tolerance: 0.000174, max_angle_deg: 3.07}}
  direction: $direction
cutting: {spindle_rpm: 20, timing: constant_rpm}
machine: $tmp/slow-c-lathe.yaml
outputs: {nc: true, report: true}
YAML
  rm -rf "$tmp/out"
  "$freeturn" run "$tmp/tilted.yaml" -o "$tmp/out" --quiet || { echo "FAIL: $direction: the run failed"; fail=1; continue; }
  report="$tmp/out/tilted.report.json"
  cycle=$("$py" -c 'import json, sys; print(json.load(open(sys.argv[1]))["passes"][-1]["cycle_time_s"])' "$report")
  if "$py" "$src/tests/jobs/nc_dynamics.py" "$tmp/out/tilted.slow-c-lathe.nc" "$tmp/slow-c-lathe.yaml" moore \
       --cycle "$cycle" > "$tmp/dyn.txt"; then
    echo "$direction: $(head -1 "$tmp/dyn.txt")"
  else
    echo "FAIL: $direction: the program exceeds its machine:"; cat "$tmp/dyn.txt"; fail=1
  fi
  # The speed the start from rest allows, in closed form (°/s to rpm: /6).
  "$py" -c 'import json, math, sys
rpm = json.load(open(sys.argv[1]))["passes"][-1]["constant_rpm"]["max_rpm"]
expected = math.sqrt(0.98 * 2600 * 3.07) / 6
print(f"  {rpm:.4f} rpm against {expected:.4f} from the start'"'"'s closed form")
sys.exit(abs(rpm / expected - 1) > 1e-3)' "$report" ||
    { echo "FAIL: $direction: the stop, not the start, sets the speed"; fail=1; }
  limited=$("$py" -c 'import json, sys; print(json.load(open(sys.argv[1]))["passes"][-1]["constant_rpm"]["limited_by"])' "$report")
  echo "  the speed is set by: $limited"
  # The start and the stop allow the same speed here, to rounding: either may be named
  # (tests/machine/axis_mapper_test.cpp names the stop where it alone sets the speed).
  if [[ "$limited" != "C acceleration"* ]]; then
    echo "FAIL: $direction: the report does not name C's acceleration"; fail=1
  fi
  # The warning says what scheduled timing would keep: this machine writes a time a block.
  "$py" -c 'import json, sys; w = [w["message"] for w in json.load(open(sys.argv[1]))["warnings"] if w["kind"] == "spindle_speed"]; print(w[0]); sys.exit("with cutting.timing: scheduled it would run at 20 rpm" not in w[0])' "$report" ||
    { echo "FAIL: $direction: the spindle speed warning does not point to scheduled timing"; fail=1; }
done
# The same lathe under PVT (the Precitech dialect with a time word): its program runs at
# one speed, and its last cubic ends at its one-sided velocity, from which the axes stop
# over the last block's time. The last two steps are evened there ([L/2, L/2]), so no
# block is under half a step and the stop asks at most twice the start: at least
# 14.741/√2 = 10.42 rpm. Read back from the NC's cubics alone (tests/jobs/nc_pvt_dynamics.py).
# Before the stop was judged, the edge-to-centre program ran at 14.74 rpm and its stop asked
# C for about 40 000 °/s²; judged, with its last block of 0.195°, it ran at 3.71 rpm.
sed -e 's/^name: slow-c-lathe/name: slow-c-pvt/' -e 's/^plugin: moore/plugin: precitech/' \
    -e 's/^interpolation: linear/interpolation: pvt\nblock_times: varying/' -e '/^moore:/,$d' \
    "$tmp/slow-c-lathe.yaml" > "$tmp/slow-c-pvt.yaml"
printf 'precitech:\n  header: "; PVT on"\n  footer: "; end of data"\n  time_word: T\n' >> "$tmp/slow-c-pvt.yaml"
for direction in edge_to_centre centre_to_edge; do
  sed -e "s/^  direction: .*/  direction: $direction/" -e "s|^machine: .*|machine: $tmp/slow-c-pvt.yaml|" \
      "$tmp/tilted.yaml" > "$tmp/tilted_pvt.yaml"
  rm -rf "$tmp/out"
  "$freeturn" run "$tmp/tilted_pvt.yaml" -o "$tmp/out" --quiet || { echo "FAIL: PVT $direction: the run failed"; fail=1; continue; }
  if "$py" "$src/tests/jobs/nc_pvt_dynamics.py" "$tmp/out/tilted.slow-c-pvt.nc" "$tmp/slow-c-pvt.yaml" T > "$tmp/dyn.txt"; then
    echo "PVT $direction: $(tail -1 "$tmp/dyn.txt")"
  else
    echo "FAIL: PVT $direction: the program exceeds its machine:"; cat "$tmp/dyn.txt"; fail=1
  fi
  "$py" -c 'import json, math, sys
rpm = json.load(open(sys.argv[1]))["passes"][-1]["constant_rpm"]["max_rpm"]
floor = math.sqrt(0.98 * 2600 * 3.07) / 6 / math.sqrt(2)
print(f"  {rpm:.4f} rpm, at least {floor:.4f}")
sys.exit(rpm < floor)' "$tmp/out/tilted.report.json" ||
    { echo "FAIL: PVT $direction: a short last block sets the speed"; fail=1; }
done
# Equal angles (120 a turn, 3°) and equal arcs (0.1 mm) on the same sphere and lathes. Their
# steps were a lattice or a length to the end, and the path's last step whatever was left:
# at 120 a turn the linear program ran at 2.14 rpm edge to centre, its stop over a 0.065°
# block setting the speed. Their last steps are now laid out as the chord rule's (in 0.98
# of an equal arc's step). Read from the NC alone: the C steps of the first block and of the
# last three, and the speed the report names against the closed form from the start and
# the stop, √(0.98 · 2600 · min(first, last)) °/s (linear: every step's C at one speed binds
# only at the start and the stop). The last step is at least 0.97 of the fourth from the end
# (linear), and none of the last three under 0.48 of it (both).
for points in "equal_angle: {per_rev: 120}" "equal_arc: {length: 0.1}"; do
  for machine in slow-c-lathe slow-c-pvt; do
    for direction in edge_to_centre centre_to_edge; do
      sed -e "s/^  direction: .*/  direction: $direction/" -e "s|^machine: .*|machine: $tmp/$machine.yaml|" \
          -e "s/^  points: .*/  points: {$points}/" "$tmp/tilted.yaml" > "$tmp/tilted_rule.yaml"
      rm -rf "$tmp/out"
      what="$points, $machine, $direction"
      "$freeturn" run "$tmp/tilted_rule.yaml" -o "$tmp/out" --quiet || { echo "FAIL: $what: the run failed"; fail=1; continue; }
      nc="$tmp/out/tilted.$machine.nc"
      if [[ $machine == slow-c-pvt ]]; then
        "$py" "$src/tests/jobs/nc_pvt_dynamics.py" "$nc" "$tmp/$machine.yaml" T > "$tmp/dyn.txt"
      else
        cycle=$("$py" -c 'import json, sys; print(json.load(open(sys.argv[1]))["passes"][-1]["cycle_time_s"])' "$tmp/out/tilted.report.json")
        "$py" "$src/tests/jobs/nc_dynamics.py" "$nc" "$tmp/$machine.yaml" moore --cycle "$cycle" > "$tmp/dyn.txt"
      fi || { echo "FAIL: $what: the program exceeds its machine:"; cat "$tmp/dyn.txt"; fail=1; }
      "$py" - "$nc" "$tmp/out/tilted.report.json" "$machine" "$what" <<'PY' || fail=1
import json, math, re, sys
nc, report, machine, what = sys.argv[1:5]
c = []
for line in open(nc):
    if line.lstrip().startswith(("(", ";")):
        continue
    m = re.search(r"C(-?[0-9.]+)", line)
    if m and re.search(r"X-?[0-9.]", line):
        c.append(float(m.group(1)))
# C is wrapped to [0, 360): unwrap, the spiral turns one way.
steps = [((b - a) % 360.0) for a, b in zip(c, c[1:])]
while steps and steps[0] == 0:  # the approach's blocks, at the start's C
    steps.pop(0)
first, last, before = steps[0], steps[-1], steps[-4]
rpm = json.load(open(report))["passes"][-1]["constant_rpm"]["max_rpm"]
ok = min(steps[-3:]) >= 0.48 * before
line = f"{what}: first {first:.5f}°, last three {[round(s, 5) for s in steps[-3:]]}, before them {before:.5f}°; {rpm:.4f} rpm"
if machine == "slow-c-lathe":
    ok = ok and last >= 0.97 * before
    expected = math.sqrt(0.98 * 2600 * min(first, last)) / 6
    ok = ok and abs(rpm / expected - 1) <= 1e-3
    line += f" against {expected:.4f} from the start and the stop"
else:
    floor = math.sqrt(0.98 * 2600 * 0.48 * min(first, before)) / 6
    ok = ok and rpm >= floor
    line += f", at least {floor:.4f}"
print(("" if ok else "FAIL: ") + line)
sys.exit(0 if ok else 1)
PY
    done
  done
done
exit $fail
