#!/usr/bin/env bash
# The freeturn command: help, version, exit codes, messages on stderr, no output on error.
set -uo pipefail
freeturn="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail=0
expect() {  # description, expected exit code, actual exit code
  if [[ "$2" != "$3" ]]; then echo "FAIL: $1: exit $3, expected $2"; fail=1; fi
}
contains() {  # description, haystack file, needle
  if ! grep -qF -- "$3" "$2"; then echo "FAIL: $1: '$3' not in:"; cat "$2"; fail=1; fi
}
# The deepest the edge goes below the design, read from a program alone by one of
# tests/jobs' readers (they share no code with freeturn), against a limit in nm; skipped
# where NumPy is missing.
below_at_most() {  # description, limit (nm), reader, the reader's arguments...
  local what=$1 limit=$2 reader=$3 deepest
  shift 3
  [[ -x /usr/bin/python3 ]] && /usr/bin/python3 -c "import numpy" 2> /dev/null || return 0
  deepest=$(/usr/bin/python3 "$src/tests/jobs/$reader" "$@")
  [[ $deepest =~ ^-?[0-9]+(\.[0-9]+)?$ ]] || { echo "FAIL: $what: the reader printed '$deepest'"; fail=1; return 0; }
  awk -v d="$deepest" -v l="$limit" 'BEGIN { exit !(d < l) }' ||
    { echo "FAIL: $what goes $deepest nm below the design"; fail=1; }
}

"$freeturn" --help > "$tmp/help" 2>&1; expect "--help" 0 $?
contains "--help lists sample" "$tmp/help" "sample"
"$freeturn" --version > "$tmp/version"; expect "--version" 0 $?
version="$(sed -n 's/^project(freeturn VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")"
contains "--version prints the project version" "$tmp/version" "freeturn $version"
"$freeturn" > /dev/null 2>&1; expect "no arguments" 2 $?
"$freeturn" frobnicate 2> "$tmp/err"; expect "unknown command" 2 $?
contains "unknown command names it" "$tmp/err" "unknown command 'frobnicate'"
"$freeturn" sample > /dev/null 2>&1; expect "sample without a job" 2 $?

# The demo job runs and writes its CSV.
"$freeturn" sample "$src/configs/jobs/demo_asphere.yaml" -o "$tmp/out" --grid 11 > "$tmp/log"
expect "demo job" 0 $?
rows=$(($(wc -l < "$tmp/out/demo_asphere.surface.csv") - 1))
# An 11 x 11 grid on [-10, 10]^2 keeps the points with x^2 + y^2 <= 100 (step 2 mm):
# count of integer pairs (i, j) in [-5, 5]^2 with i^2 + j^2 <= 25 is 81.
[[ "$rows" == 81 ]] || { echo "FAIL: demo rows $rows, expected 81"; fail=1; }

# A bad job: message file:line:col on stderr, exit 2, no output file.
cat > "$tmp/bad.yaml" <<'YAML'
name: bad
aperture:
  outer_radius: 5
surface:
  type: sphere
  radius: 20
  colour: blue
YAML
"$freeturn" sample "$tmp/bad.yaml" -o "$tmp/bad" > "$tmp/out.txt" 2> "$tmp/err"
expect "bad job" 2 $?
contains "bad job message" "$tmp/err" "$tmp/bad.yaml:7:3: unknown key 'colour' in surface"
[[ ! -s "$tmp/out.txt" ]] || { echo "FAIL: bad job printed to stdout"; fail=1; }
[[ ! -e "$tmp/bad/bad.surface.csv" ]] || { echo "FAIL: bad job left an output"; fail=1; }

# ncdiff: the same program reformatted and re-commented is the same (0); an axis word
# moved beyond the tolerance differs (1, naming the lines); not NC is bad input (2).
printf '%%\nG21 G18\nG1 X1.000000 Z-0.500000 C10.0 F100\nG1 X0.9 Z-0.4\nM2\n' > "$tmp/a.nc"
printf 'G18 G21 (units)\nG01 Z-0.5 X1 C10 F100.0\nN20 G1 X0.900000 Z-0.400000 ; move\nM02\n' > "$tmp/b.nc"
printf '%%\nG21 G18\nG1 X1.000000 Z-0.500000 C10.0 F100\nG1 X0.9001 Z-0.4\nM2\n' > "$tmp/c.nc"
"$freeturn" ncdiff "$tmp/a.nc" "$tmp/b.nc" > "$tmp/stdout"; expect "ncdiff same" 0 $?
"$freeturn" ncdiff "$tmp/a.nc" "$tmp/c.nc" > "$tmp/stdout"; expect "ncdiff moved" 1 $?
# A tolerance of nan passed CLI11's range check and called the moved word the same (exit 0).
"$freeturn" ncdiff "$tmp/a.nc" "$tmp/c.nc" --tolerance nan > /dev/null 2> "$tmp/err"; expect "ncdiff --tolerance nan" 2 $?
contains "ncdiff --tolerance nan says why" "$tmp/err" "--tolerance: must be a finite number in [0, 1e+06], not 'nan'"
"$freeturn" simulate "$src/configs/jobs/oap_segment.yaml" -o "$tmp/simnan" --radial-step nan > /dev/null 2> "$tmp/err"; expect "simulate --radial-step nan" 2 $?
[[ ! -e "$tmp/simnan" ]] || { echo "FAIL: a refused simulate left output"; fail=1; }
contains "ncdiff names the line" "$tmp/stdout" "a.nc:4 vs $tmp/c.nc:4: X 0.9"
echo "hello, world" > "$tmp/d.txt"
"$freeturn" ncdiff "$tmp/a.nc" "$tmp/d.txt" > /dev/null 2> "$tmp/err"; expect "ncdiff not NC" 2 $?
# A device or a pipe is no program: /dev/zero was read until memory ran out, a pipe's open
# blocked for good.
timeout 10 "$freeturn" ncdiff /dev/zero "$tmp/a.nc" > /dev/null 2> "$tmp/err"; expect "ncdiff /dev/zero" 2 $?
contains "ncdiff /dev/zero says why" "$tmp/err" "/dev/zero: is not a regular file"
mkfifo "$tmp/pipe.nc"
timeout 10 "$freeturn" ncdiff "$tmp/a.nc" "$tmp/pipe.nc" > /dev/null 2> "$tmp/err"; expect "ncdiff a pipe" 2 $?

# plugins: the iso post and its three machines are found in the build tree.
"$freeturn" plugins > "$tmp/stdout"; expect "plugins" 0 $?
contains "iso post listed" "$tmp/stdout" "libfreeturn_post_iso.so)  ok"
contains "iso machine listed" "$tmp/stdout" "iso-lathe-xzcb           axes XZCB  C accumulating, B -60…60°"

# run and check at a spindle speed the machine cannot follow (20 000 rpm, the most a job may ask, on the iso lathe):
# - scheduled (the default), each block slows to what the limits allow: the program is
#   written and passes, its cycle far above 60·turns/20000 s;
# - timing: constant_rpm, the program runs at the highest speed every block allows;
# - enforce_dynamics: false, it is written at 20 000 rpm, but run exits 1 and says UNSAFE
#   with the limit, and check says UNSAFE (never PASS) and exits 1.
sed 's/spindle_rpm: 20/spindle_rpm: 20000/' "$src/configs/jobs/oap_segment.yaml" > "$tmp/fast.yaml"
"$freeturn" run "$tmp/fast.yaml" -o "$tmp/fast" > "$tmp/stdout" 2> "$tmp/err"; expect "run too fast, scheduled" 0 $?
contains "scheduled run passes" "$tmp/fast/oap_segment.report.json" '"status": "PASS"'
contains "scheduled run says so" "$tmp/fast/oap_segment.report.json" '"scheduled": true'
"$freeturn" check "$tmp/fast.yaml" > "$tmp/stdout"; expect "check too fast, scheduled" 0 $?
contains "check pass" "$tmp/stdout" "PASS: "
sed 's/spindle_rpm: 20000/spindle_rpm: 20000\n  timing: constant_rpm/' "$tmp/fast.yaml" > "$tmp/constant.yaml"
"$freeturn" run "$tmp/constant.yaml" -o "$tmp/constant" > /dev/null 2> "$tmp/err"; expect "constant rpm" 0 $?
read -r rpm max < <(python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))
print(r["timing"]["spindle_rpm"], r["passes"][-1]["constant_rpm"]["max_rpm"])' "$tmp/constant/oap_segment.report.json")
# The highest feasible speed less a billionth (docs/machines.md, "One constant speed").
awk -v a="$rpm" -v b="$max" 'BEGIN { exit !(a > 0 && a < 20000 && a <= b && a >= b * (1 - 1e-8)) }' ||
  { echo "FAIL: constant rpm: programmed $rpm rpm, highest feasible $max"; fail=1; }
sed 's/spindle_rpm: 20000/spindle_rpm: 20000\n  enforce_dynamics: false/' "$tmp/fast.yaml" > "$tmp/unsafe.yaml"
"$freeturn" run "$tmp/unsafe.yaml" -o "$tmp/unsafe" > /dev/null 2> "$tmp/err"; expect "run over the limits" 1 $?
contains "run says UNSAFE with the limit" "$tmp/err" "UNSAFE: finish: at 20000 rpm the program exceeds the machine's limits"
contains "the unsafe report says so" "$tmp/unsafe/oap_segment.report.json" '"status": "UNSAFE"'
"$freeturn" check "$tmp/unsafe.yaml" > "$tmp/stdout"; expect "check over the limits" 1 $?
contains "check verdict" "$tmp/stdout" "UNSAFE: finish: at 20000 rpm"
if grep -q "^PASS" "$tmp/stdout"; then echo "FAIL: check printed PASS for an unsafe program"; fail=1; fi
# A profile on the Precitech's PVT controller: the cubics through the blocks, timed by the
# feed, must stay within the machine too. The ring at 1 400 mm/min (within X's 25 mm/s)
# starts from rest into a first block of 1.6 ms, asking X for 14 477 mm/s² against 500
# (an independent reader of the cubics from the NC agreed). Its first block allows
# 257.57 mm/min, but the stop after its last block (X from −0.034642 to 0 on the axis, Z
# 0.001303 lower: v = ΔX/t, t = the chord over the feed, stopped over t) allows only
# F = 60·chord·√(490/ΔX) = 247.38 mm/min at the 0.98 share of 500 mm/s². It is refused at
# cutting.feed with the feed every block holds, and that feed runs. Before, it was written
# under a PASS; then refused at its first block with 257.56, whose program's last block
# (from −0.026637, before the last two steps were evened) stopped X at 690 mm/s².
sed 's/feed: 2.0 /feed: 1400 /; s/period: 2.5 /period: 0.8 /; s/roughing: \[0.01\]/roughing: []/' \
  "$src/configs/jobs/sinusoidal_ring.yaml" > "$tmp/ring_fast.yaml"
(cd "$src/configs/jobs" && "$freeturn" run "$tmp/ring_fast.yaml" -o "$tmp/ring_fast" --quiet) 2> "$tmp/err"
expect "PVT profile over the acceleration" 2 $?
contains "PVT profile refused at the feed" "$tmp/err" "ring_fast.yaml:20:9: cutting.feed: "
contains "PVT profile names the feed that holds" "$tmp/err" "X acceleration on the controller's PVT cubics (the stop after the last block) exceeds the machine's limit at cutting.feed 1400 mm/min: give a feed of at most 247.37"
[[ -z "$(ls -A "$tmp/ring_fast" 2> /dev/null)" ]] || { echo "FAIL: the refused profile wrote files"; fail=1; }
sed 's/feed: 1400 /feed: 247.3 /' "$tmp/ring_fast.yaml" > "$tmp/ring_held.yaml"
(cd "$src/configs/jobs" && "$freeturn" run "$tmp/ring_held.yaml" -o "$tmp/ring_held" --quiet) 2> "$tmp/err"
expect "PVT profile at the feed that holds" 0 $?
# Read back from its NC alone (tests/jobs/nc_pvt_dynamics.py): each axis's cubic Hermite
# through the blocks, timed by their X-Z chords at the feed, velocities the central
# differences over the neighbours' times (one-sided at the ends), from rest into the first
# block and to rest after the last, each over that block's time. X's largest acceleration
# lies in (480, 500] mm/s².
python3 "$src/tests/jobs/nc_pvt_dynamics.py" "$tmp/ring_held/sinusoidal_ring.precitech-nanoform-250.nc" \
  "$src/postprocessors/precitech/machines/precitech-nanoform-250.yaml" feed > "$tmp/dyn.txt"
echo "PVT ring at 247.3 mm/min: $(grep '^X:' "$tmp/dyn.txt")"
x_acceleration=$(sed -n 's/^X:.* acceleration \([0-9.e+-]*\) of .*/\1/p' "$tmp/dyn.txt")
awk -v a="$x_acceleration" 'BEGIN { exit !(a > 480 && a <= 500) }' ||
  { echo "FAIL: the PVT profile's cubics exceed X's 500 mm/s²"; cat "$tmp/dyn.txt"; fail=1; }
# With the limits turned off it is written, and UNSAFE with the feed that would hold.
sed 's/feed: 1400 /feed: 1400\n  enforce_dynamics: false/' "$tmp/ring_fast.yaml" > "$tmp/ring_unsafe.yaml"
(cd "$src/configs/jobs" && "$freeturn" run "$tmp/ring_unsafe.yaml" -o "$tmp/ring_unsafe" --quiet) 2> "$tmp/err"
expect "PVT profile over the limits, turned off" 1 $?
contains "PVT profile off: UNSAFE with the feed" "$tmp/err" "at 1400 mm/min the program exceeds the machine's limits (enforce_dynamics: false): the highest feasible feed is 247.37"
# The CL data is written round-trip exact: each contact's θ is atan2(y, x) of its own point
# to 1e-12 mm along the arc (nine fixed decimals were 2.5 nm off at r = 5 mm).
python3 - "$tmp/fast/oap_segment.cl.csv" <<'PY' || { echo "FAIL: CL data not exact"; fail=1; }
import csv, math, sys
worst = 0.0
for row in csv.DictReader(open(sys.argv[1])):
    t, x, y = float(row["theta_rad"]), float(row["x_mm"]), float(row["y_mm"])
    r = math.hypot(x, y)
    if r > 0:
        worst = max(worst, abs(math.remainder(math.atan2(y, x) - t, 2 * math.pi)) * r)
sys.exit(0 if worst < 1e-12 else 1)
PY

# The sinusoidal ring cut as a spiral through its cone point on the 250UPL: safe (PASS),
# and the planner's prediction, the uncut residual at the cone included, bounds the
# simulated form error.
cat > "$tmp/ring_spiral.yaml" <<YAML
name: ring_spiral
aperture: {outer_radius: 1.0}
surface: {type: sinusoidal_ring, amplitude: 0.005, period: 2.5}
tool: {nose_radius: 0.5, included_angle_deg: 120}
strategy:
  mode: spiral
  spiral: planar
  pitch: 0.02
  points: {chord: {tolerance: 0.0001, max_angle_deg: 4}}
cutting: {spindle_rpm: 20}
machine: moore-nanotech-250upl
YAML
"$freeturn" simulate "$tmp/ring_spiral.yaml" -o "$tmp/ring_spiral" > "$tmp/stdout"; expect "ring spiral simulate" 0 $?
contains "ring spiral: prediction bounds the cut" "$tmp/stdout" "an upper bound"
contains "ring spiral passes" "$tmp/ring_spiral/ring_spiral.report.json" '"status": "PASS"'

# A sinusoidal ring whose troughs (concave radius 1/(Aω²) = 0.507 mm) are tighter than a
# 0.6 mm nose: no placement of the nose touches their bottoms, so it rests on both sides of
# each (docs/tool.md, "Troughs tighter than the nose"). The program leaves the bottoms and
# the report says how much; read back from the NC alone, the edge stays above the design.
# Until December 2026 it was written gouging the troughs (tests/jobs/nc_profile_gouge.py
# read it 4.5 µm deep), UNSAFE only by the gouge checks.
sed -e 's/amplitude: 0.005 /amplitude: 0.05 /' -e 's/period: 2.5 /period: 1.0 /' \
    -e 's/nose_radius: 0.5/nose_radius: 0.6/' \
    "$src/configs/jobs/sinusoidal_ring.yaml" > "$tmp/held.yaml"
"$freeturn" run "$tmp/held.yaml" -o "$tmp/held" > /dev/null 2> "$tmp/err"; expect "a ring whose troughs are tighter than the nose" 0 $?
contains "the material left is named" "$tmp/err" "hold the nose at a crease or a trough it cannot reach into: up to "
contains "the report says PASS" "$tmp/held/sinusoidal_ring.report.json" '"status": "PASS"'
contains "the uncut residual is a structured warning" "$tmp/held/sinusoidal_ring.report.json" '"kind": "uncut_residual"'
below_at_most "the held ring's edge" 10 nc_profile_gouge.py \
  "$tmp/held/sinusoidal_ring.precitech-nanoform-250.nc" sinusoidal_ring:0.05:1.0 0.6 0 60 5.0
# Its 0.6 mm nose is held still on the cone point at the centre: a PVT block there that
# repeats the last one's place would have no time (a profile's block time is its X-Z chord).
repeated="$(grep '^X' "$tmp/held/sinusoidal_ring.precitech-nanoform-250.nc" | uniq -d)"
[[ -z "$repeated" ]] || { echo "FAIL: the PVT program repeats a block in place: $repeated"; fail=1; }
# The same troughs (period 0.8 mm: 1/(Aω²) = 0.324 mm) cut by a spiral under a 0.5 mm nose
# on the Moore: held on both sides of each trough at every angle, read back from the NC
# by the edge's arc in the rake plane.
cat > "$tmp/held_spiral.yaml" <<YAML
name: held_spiral
aperture: {outer_radius: 1.5}
surface: {type: sinusoidal_ring, amplitude: 0.05, period: 0.8}
tool: {nose_radius: 0.5, included_angle_deg: 120}
strategy: {mode: spiral, spiral: planar, pitch: 0.02, points: {chord: {tolerance: 0.0002, max_angle_deg: 4}}}
cutting: {spindle_rpm: 20}
machine: moore-nanotech-250upl
YAML
"$freeturn" run "$tmp/held_spiral.yaml" -o "$tmp/held_spiral" > /dev/null 2> "$tmp/err"; expect "a spiral over troughs tighter than the nose" 0 $?
contains "the spiral's report says PASS" "$tmp/held_spiral/held_spiral.report.json" '"status": "PASS"'
below_at_most "the held spiral's edge" 10 nc_rake_gouge.py \
  "$tmp/held_spiral/held_spiral.moore-nanotech-250upl.nc" sinusoidal_ring:0.05:0.8 0.5 0 60 0 1.5

# With B following the normal no nose is held: the same troughs stop the job, and the
# message points to a fixed B, which cuts them as above.
sed -e 's/points: {chord: {tolerance: 0.0002, max_angle_deg: 4}}}/points: {chord: {tolerance: 0.0002, max_angle_deg: 4}}, b_axis: follow}/' \
    -e 's/machine: moore-nanotech-250upl/machine: moore-nanotech-350fg-b/' \
    "$tmp/held_spiral.yaml" > "$tmp/held_b.yaml"
"$freeturn" run "$tmp/held_b.yaml" -o "$tmp/held_b" > /dev/null 2> "$tmp/err"; expect "troughs tighter than the nose with B following" 2 $?
contains "the message points to a fixed B" "$tmp/err" "or cut it with b_axis: fixed, which rests the nose on both sides"
[[ -z "$(ls -A "$tmp/held_b" 2> /dev/null)" ]] || { echo "FAIL: a run stopped by bad input left files:"; ls "$tmp/held_b"; fail=1; }

# A downgraded check still marks the program UNSAFE: a sphere decentred 0.5 mm, whose
# flank about the axis faces the cut at atan(0.5/√3.75) = 14.5°, past the tool's 10°
# clearance, with the clearance check set to warning, is written, but run exits 1 and both
# commands name the worst place.
cat > "$tmp/steep.yaml" <<YAML
name: steep
aperture: {outer_radius: 0.2}
surface: {type: sphere, radius: 2.0, decenter: {x: 0.5}}
tool:
  nose_radius: 0.1
  checks: {clearance: warning}
strategy: {mode: spiral, spiral: planar, pitch: 0.01, points: {chord: {tolerance: 0.001, max_angle_deg: 5}}}
cutting: {spindle_rpm: 20}
machine: iso-lathe-xzc
YAML
"$freeturn" run "$tmp/steep.yaml" -o "$tmp/steep" > /dev/null 2> "$tmp/err"; expect "run with a downgraded check" 1 $?
contains "run says UNSAFE at the clearance" "$tmp/err" "UNSAFE: finish: clearance: "
contains "run names where" "$tmp/err" "at θ = "
[[ -f "$tmp/steep/steep.iso-lathe-xzc.nc" ]] || { echo "FAIL: a warning-only job wrote no program"; fail=1; }
contains "the report says UNSAFE" "$tmp/steep/steep.report.json" '"status": "UNSAFE"'
contains "the finding is a structured warning" "$tmp/steep/steep.report.json" '"kind": "clearance"'
"$freeturn" check "$tmp/steep.yaml" > "$tmp/stdout"; expect "check with a downgraded check" 1 $?
contains "check says UNSAFE" "$tmp/stdout" "UNSAFE: finish: clearance: "
if grep -q "^PASS" "$tmp/stdout"; then echo "FAIL: check printed PASS for an unsafe program"; fail=1; fi
# Switched off, the same check still runs and still marks it UNSAFE: `off` is read as
# `warning`.
sed 's/checks: {clearance: warning}/checks: {clearance: off}/' "$tmp/steep.yaml" > "$tmp/steep_off.yaml"
"$freeturn" run "$tmp/steep_off.yaml" -o "$tmp/steep_off" > /dev/null 2> "$tmp/err"; expect "run with the clearance check off" 1 $?
contains "run with the check off says UNSAFE at the clearance" "$tmp/err" "UNSAFE: finish: clearance: "
contains "its report says UNSAFE" "$tmp/steep_off/steep.report.json" '"status": "UNSAFE"'
# A 1 mm nose in those troughs spans the cone point and the troughs either side of it: held
# across them all by the section's overhang (section_envelope.cpp, hold_by_overhang), and
# read back above the design. (It stopped at the chord tolerance until December 2026.)
sed -e 's/amplitude: 0.005 /amplitude: 0.05 /' -e 's/period: 2.5 /period: 1.0 /' \
    -e 's/nose_radius: 0.5/nose_radius: 1.0/' \
    "$src/configs/jobs/sinusoidal_ring.yaml" > "$tmp/wide.yaml"
timeout 120 "$freeturn" run "$tmp/wide.yaml" -o "$tmp/wide" > /dev/null 2> "$tmp/err"; expect "a nose wider than the troughs" 0 $?
below_at_most "the wide nose's edge" 10 nc_profile_gouge.py \
  "$tmp/wide/sinusoidal_ring.precitech-nanoform-250.nc" sinusoidal_ring:0.05:1.0 1.0 0 60 5.0
# An 0.8 mm nose over troughs 0.3 mm apart (concave radius 1/(Aω²) = 0.228 mm), five
# periods under it: it rests on the crests, dropped onto the section where its touch
# passes each trough (section_envelope.cpp, hold_by_overhang). It stopped at the chord
# tolerance until December 2026 (no offset of a contact within 2R overhung nothing);
# now it is written and read back above the design.
sed -e 's/amplitude: 0.005 /amplitude: 0.01 /' -e 's/period: 2.5 /period: 0.3 /' \
    -e 's/nose_radius: 0.5/nose_radius: 0.8/' \
    "$src/configs/jobs/sinusoidal_ring.yaml" > "$tmp/five.yaml"
timeout 120 "$freeturn" run "$tmp/five.yaml" -o "$tmp/five" > /dev/null 2> "$tmp/err"; expect "a nose five periods wide" 0 $?
contains "it says what it leaves" "$tmp/err" "cannot reach into: up to "
below_at_most "the five-period nose's edge" 10 nc_profile_gouge.py \
  "$tmp/five/sinusoidal_ring.precitech-nanoform-250.nc" sinusoidal_ring:0.01:0.3 0.8 0 60 5.0
# Bowls of radius 0.15 mm, 0.2 mm across, under the microlens mold's 0.2 mm nose: every
# section of a bowl is tighter than the nose, which rests on its two rims across it
# (docs/tool.md, "Bowls tighter than the nose"). It stopped at the chord tolerance until
# December 2026; now it is written, leaves the bowls' bottoms (the closed form
# (R_b − √(R_b² − a²)) − (R − √(R'² − a²)) with a = 0.1 mm and R' = R + 0.1 µm: 11 517.1 nm)
# and is read back above the design. Its walls (41.8° at the rims) pass a 45° clearance.
sed -e 's/lens_radius: 0.6 /lens_radius: 0.15 /' -e 's/outer_radius: 1.0 /outer_radius: 0.4 /' \
    -e 's/included_angle_deg: 120/included_angle_deg: 120\n  clearance_angle_deg: 45/' \
    "$src/configs/jobs/microlens_mold.yaml" > "$tmp/bowls.yaml"
timeout 300 "$freeturn" run "$tmp/bowls.yaml" -o "$tmp/bowls" > /dev/null 2> "$tmp/err"; expect "bowls tighter than the nose" 0 $?
contains "they leave the bowls' bottoms" "$tmp/err" "up to 11517."
below_at_most "the nose over the tight bowls" 1 nc_rake_gouge.py \
  "$tmp/bowls/microlens_mold.moore-nanotech-250upl.nc" microlens_array:0.15:0.2:0.25:0.4 0.2 0 60 0 0.4
# The same bowls on a lathe that interpolates PVT cubics (the Moore's axes in the Precitech
# dialect with a time word a block), read back along the controller's cubics: the nose
# stays above the design between the blocks too, not only on the chords.
sed -e 's/^name: .*/name: bowl-pvt/' -e 's/^plugin: moore/plugin: precitech/' \
    -e 's/^interpolation: linear/interpolation: pvt\nblock_times: varying/' -e '/^moore:/,$d' \
    "$src/postprocessors/moore/machines/moore-nanotech-250upl.yaml" > "$tmp/bowl-pvt.yaml"
printf 'precitech:\n  header: "; PVT on"\n  footer: "; end of data"\n  time_word: T\n' >> "$tmp/bowl-pvt.yaml"
sed -e "s|^machine: .*|machine: $tmp/bowl-pvt.yaml|" -e 's/outer_radius: 0.4 /outer_radius: 0.3 /' \
    "$tmp/bowls.yaml" > "$tmp/bowls_pvt.yaml"
timeout 300 "$freeturn" run "$tmp/bowls_pvt.yaml" -o "$tmp/bowls_pvt" > /dev/null 2> "$tmp/err"; expect "bowls tighter than the nose, PVT" 0 $?
below_at_most "the PVT nose over the tight bowls" 1 nc_rake_gouge.py \
  "$tmp/bowls_pvt/microlens_mold.bowl-pvt.nc" microlens_array:0.15:0.2:0.25:0.3 0.2 0 60 0 0.3
# Lenslet arrays fine beside the nose.
# Sections that meet more creases within the nose's reach than a crease list held
# (docs/tool.md, "Sections that meet more creases than a list holds"): domes 18 µm across
# at a 20 µm pitch under a 0.5 mm nose, about a hundred rims under it, and narrow bowls
# barely tighter than a 0.271 mm nose, 38 creases within the hold's reach. The lists kept
# the creases in the order found, not the lowest, and both stopped at the chord tolerance
# until December 2026; now both are written and read back above the design.
# A planar spiral on the Moore by the chord rule (0.2 µm, 4° cap), written, and its edge read
# back from the NC no more than 1 nm below the design.
spiral_written() {  # name, surface (a flow map), nose, aperture, spiral pitch, reader's design, report
  cat > "$tmp/$1.yaml" <<JOB
name: $1
aperture: {outer_radius: $4}
surface: $2
tool: {nose_radius: $3, included_angle_deg: 90, clearance_angle_deg: 45}
strategy:
  mode: spiral
  spiral: planar
  pitch: $5
  points: {chord: {tolerance: 0.0002, max_angle_deg: 4}}
cutting: {spindle_rpm: 20}
machine: moore-nanotech-250upl
outputs: {nc: true, report: $7}
JOB
  timeout 300 "$freeturn" run "$tmp/$1.yaml" -o "$tmp/$1" > /dev/null 2> "$tmp/err"
  expect "$1: written" 0 $?
  below_at_most "$1: the edge" 1 nc_rake_gouge.py "$tmp/$1/$1.moore-nanotech-250upl.nc" "$6" "$3" 0 45 0 "$4"
}
fine_job() {  # name, lens radius, diameter, pitch, nose, aperture, spiral pitch
  spiral_written "$1" "{type: microlens_array, lens_radius: $2, lens_diameter: $3, pitch: $4, lattice: square}" \
    "$5" "$6" "$7" "microlens_array:$2:$3:$4:$6" false
}
fine_job fine_domes -0.6 0.018 0.02 0.5 0.25 0.0031
fine_job narrow_bowls 0.2563 0.0896 0.1296 0.2711 0.52 0.0031
# Domes 0.18 mm across at a 0.2 mm pitch under a 3 mm nose: held between two domes, the
# nose reached 84 nm into a third's crest, and the chord rule stopped (docs/tool.md, "A
# nose wider than the lenslets"); now it rests on the crests either side of the gap.
fine_job wide_nose_domes -1 0.18 0.2 3 1 0.01
# A sinusoidal grid (A 5 µm, λ 0.3 × 0.4 mm) whose troughs bend to 1/(A kx²) = 0.456 mm, barely
# tighter than the 0.5 mm nose: their tight stretches are mostly narrower than the view's
# samples (docs/tool.md, "Stretches between two samples"). The local gouge check failed the
# first touch in one (exit 1, nothing written); now the nose rests on both sides, and the
# report names what is left.
spiral_written grid_troughs "{type: sinusoidal_grid, amplitude: 0.005, wavelength_x: 0.3, wavelength_y: 0.4}" \
  0.5 1.0 0.02 "sinusoidal_grid:0.005:0.3:0.4" true
contains "grid_troughs: the report names the material left" "$tmp/grid_troughs/grid_troughs.report.json" \
  "the design is unreachable there; the program does not gouge"
# Troughs 10 µm apart (concave radius 1/(Aω²) = 2.5 µm) under the same nose bend faster than the view
# of tight troughs samples them (path/tight_troughs.hpp): no step meets the tolerance. In
# PVT mode (this machine's) the planner once took slivers of no length there without end;
# now it stops as linear motion does: exit 2, the place named, nothing written.
sed -e 's/amplitude: 0.005 /amplitude: 0.001 /' -e 's/period: 2.5 /period: 0.01 /' \
    -e 's/nose_radius: 0.5/nose_radius: 0.8/' \
    "$src/configs/jobs/sinusoidal_ring.yaml" > "$tmp/crawl.yaml"
timeout 120 "$freeturn" run "$tmp/crawl.yaml" -o "$tmp/crawl" > /dev/null 2> "$tmp/err"; expect "PVT run where no step meets the tolerance" 2 $?
contains "it names the tolerance" "$tmp/err" "cannot meet the chord tolerance 0.1 µm"
contains "and where" "$tmp/err" "r = "
# And why: the section's concave radius (the tightest of 65 samples across the nose, tens
# of micrometres at most) against the 0.8 mm nose, and a radius to use instead.
contains "and why: the section's concave radius against the nose's" "$tmp/err" \
  "the design's section bends to a concave radius of 0.0"
contains "and what to use instead" "$tmp/err" "use a nose radius under 0.0"
[[ -z "$(ls -A "$tmp/crawl" 2> /dev/null)" ]] || { echo "FAIL: a run stopped by bad input left files:"; ls "$tmp/crawl"; fail=1; }
# With the checks as errors (the default) the steep job stops at the first finding: exit 1
# (a check failed, not bad input), the place named, nothing written.
sed '/checks: {clearance: warning}/d' "$tmp/steep.yaml" > "$tmp/steep_error.yaml"
"$freeturn" run "$tmp/steep_error.yaml" -o "$tmp/steep_error" > /dev/null 2> "$tmp/err"; expect "run stopped by a check" 1 $?
contains "run names the check and where" "$tmp/err" "clearance check: "
contains "run names where" "$tmp/err" "r = "
[[ -z "$(ls -A "$tmp/steep_error" 2> /dev/null)" ]] || { echo "FAIL: a run stopped by a check left files:"; ls "$tmp/steep_error"; fail=1; }
"$freeturn" check "$src/configs/jobs/oap_segment.yaml" > "$tmp/stdout"; expect "check ok" 0 $?
contains "check pass" "$tmp/stdout" "PASS: oap_segment on iso-lathe-xzc"
"$freeturn" check "$tmp/bad.yaml" > /dev/null 2>&1; expect "check bad job" 2 $?

# simulate: the off-axis parabola's finishing cut; its form error is the scallop of a
# 0.5 mm nose at 0.05 mm pitch, R − √(R² − f²/4) = 625.4 nm on a flat (the segment is
# nearly flat), and the residual grid and coloured mesh are written.
"$freeturn" simulate "$src/configs/jobs/oap_segment.yaml" -o "$tmp/sim" > "$tmp/stdout"; expect "simulate" 0 $?
pv=$(sed -n 's/.*form error PV \([0-9.]*\) nm.*/\1/p' "$tmp/stdout")
awk -v pv="$pv" 'BEGIN { exit !(pv > 615 && pv < 635) }' || { echo "FAIL: simulated PV '$pv' nm, expected about 625"; fail=1; }
for f in oap_segment.residual.csv oap_segment.residual.ply oap_segment.report.json oap_segment.report.html; do
  [[ -s "$tmp/sim/$f" ]] || { echo "FAIL: simulate wrote no $f"; fail=1; }
done
contains "simulation figures in the report" "$tmp/sim/oap_segment.report.json" '"source": "simulation"'
# The scallop dominates this cut: the planner's prediction bounds it within 10%, and the
# worst places say so.
contains "prediction bound" "$tmp/stdout" "an upper bound within 10%"
contains "worst place cause" "$tmp/stdout" "(scallop)"
contains "worst places in the report" "$tmp/sim/oap_segment.report.json" '"cause": "scallop"'
# Figure and finish apart: the cusps are the finish (≈ 625 nm), the figure is what the
# chord error leaves (under its 100 nm tolerance), not the cusps again.
python3 - "$tmp/sim/oap_segment.report.json" <<'PY' || { echo "FAIL: figure and finish not apart"; fail=1; }
import json, sys
e = json.load(open(sys.argv[1]))["form_error"]
ok = 615 < e["finish_nm"]["pv"] < 635 and e["figure_nm"]["pv"] < 100 and e["split"]["resolved"]
sys.exit(0 if ok else 1)
PY
contains "figure in the simulate output" "$tmp/stdout" "figure (the residual's mean over a pitch) PV"
# On a PVT machine the controller's cubics: the prediction still bounds the simulation.
sed 's/^machine: .*/machine: precitech-nanoform-250/' "$src/configs/jobs/oap_segment.yaml" > "$tmp/oap_pvt.yaml"
(cd "$src/configs/jobs" && "$freeturn" simulate "$tmp/oap_pvt.yaml" -o "$tmp/sim_pvt") > "$tmp/stdout"; expect "simulate pvt" 0 $?
contains "prediction bound (pvt)" "$tmp/stdout" "an upper bound within 10%"
# The same on one thread: the same residual grid, byte for byte.
"$freeturn" simulate "$src/configs/jobs/oap_segment.yaml" -o "$tmp/sim1" --threads 1 > /dev/null; expect "simulate 1 thread" 0 $?
cmp -s "$tmp/sim/oap_segment.residual.csv" "$tmp/sim1/oap_segment.residual.csv" || { echo "FAIL: the residual grid differs on one thread"; fail=1; }
"$freeturn" simulate "$src/configs/jobs/oap_segment.yaml" -o "$tmp/sim0" --threads 0 > /dev/null 2>&1; expect "simulate --threads 0" 2 $?
[[ ! -e "$tmp/sim0" ]] || { echo "FAIL: a refused simulate left output"; fail=1; }

# The compensated example with a B-spline after its Zernike terms: the B-spline had ended at
# the aperture's edge, and the spiral's last turn, projected along the tilted base normal,
# landed past it ("misses the design surface"); its cold rays missed inside the data too.
sed -e "s|fit: {zernike: 21}|fit: {zernike: 21, bspline: {control_points: 24}}|" \
    -e "s|\.\./data/|$src/configs/data/|" \
    "$src/configs/jobs/compound_eye_compensated.yaml" > "$tmp/bspline.yaml"
grep -q "bspline: {control_points: 24}" "$tmp/bspline.yaml" || { echo "FAIL: the B-spline job was not made"; fail=1; }
"$freeturn" check "$tmp/bspline.yaml" --quiet > "$tmp/out.txt" 2> "$tmp/err"
expect "a compensated job with a B-spline" 0 $?
contains "a compensated job with a B-spline passes" "$tmp/out.txt" "PASS"

# Progress: on a terminal (a pseudo-terminal from script(1)) run shows points and rate on
# stderr; with --quiet, or when stderr is not a terminal, it shows none.
if command -v script > /dev/null; then
  FREETURN_PROGRESS_INTERVAL=0 script -qec "'$freeturn' run '$src/configs/jobs/oap_segment.yaml' -o '$tmp/p1'" /dev/null > "$tmp/tty.txt"
  contains "progress on a terminal" "$tmp/tty.txt" "points/s"
  FREETURN_PROGRESS_INTERVAL=0 script -qec "'$freeturn' run '$src/configs/jobs/oap_segment.yaml' -o '$tmp/p2' --quiet" /dev/null > "$tmp/tty.txt"
  ! grep -q "points/s" "$tmp/tty.txt" || { echo "FAIL: --quiet still shows progress"; fail=1; }
  FREETURN_PROGRESS_INTERVAL=0 "$freeturn" run "$src/configs/jobs/oap_segment.yaml" -o "$tmp/p3" > /dev/null 2> "$tmp/err"
  ! grep -q "points/s" "$tmp/err" || { echo "FAIL: progress shown off a terminal"; fail=1; }
fi

exit $fail
