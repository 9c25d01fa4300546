#!/usr/bin/env bash
# A tool whose edge sits h above the spindle line cuts with an arc in the rake plane, not
# in a radial plane (docs/tool.md, "Centre height"). Two jobs with h = 10 µm are run and
# their programs read back by tests/jobs/nc_rake_gouge.py, which sweeps that arc from the
# NC words alone: a sphere of radius 5 mm decentred by 1 mm (slopes to 0.44), chord rule,
# was cut 588 nm into the design near the axis before the nose was laid in the rake plane;
# the compound eye's lenslets at 1000 points a turn 6.1 nm into their rims. Both must
# stay above the design, and `simulate --program` must find them so. Domes with one on the
# axis, h = −0.2 µm, must plan and stay above the design too. A profile on the PVT
# Precitech is read back along the controller's cubics.
# usage: centre_height_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Debian's python3 has python3-numpy (scripts/setup.sh); another first on PATH may not.
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
"$py" -c "import numpy" 2> /dev/null || { echo "SKIP: python3 with numpy"; exit 77; }
fail=0
job() {  # name aperture surface points
  cat > "$tmp/$1.yaml" <<YAML
name: $1
aperture: $2
surface: $3
tool: {nose_radius: 0.2, included_angle_deg: 100, clearance_angle_deg: 25, centre_height: 0.01}
strategy:
  mode: spiral
  spiral: space
  pitch: $4
  points: $5
cutting: {spindle_rpm: 10}
machine: moore-nanotech-250upl
outputs: {nc: true, report: false}
YAML
  "$freeturn" run "$tmp/$1.yaml" -o "$tmp/$1" --quiet || { echo "FAIL: $1: the run failed"; fail=1; return 1; }
}
check() {  # name design r_min r_max
  local deepest
  deepest=$("$py" "$src/tests/jobs/nc_rake_gouge.py" "$tmp/$1/$1.moore-nanotech-250upl.nc" "$2" 0.2 0.01 50 "$3" "$4") || { fail=1; return; }
  echo "$1: the edge's deepest below the design: $deepest nm"
  "$py" -c "import sys; sys.exit(0 if float('$deepest') <= 0 else 1)" || { echo "FAIL: $1 cuts into the design"; fail=1; }
  # freeturn's own simulation of the program, which sweeps the arc in the rake plane too.
  "$freeturn" simulate "$tmp/$1.yaml" --program "$tmp/$1/$1.moore-nanotech-250upl.nc" -o "$tmp/sim-$1" \
    --columns 720 --quiet > /dev/null || { echo "FAIL: $1: simulate --program does not pass it"; fail=1; }
}
job decentred "{outer_radius: 1.0, inner_radius: 0.1}" "{type: sphere, radius: 5.0, decenter: {x: 1.0}}" 0.005 \
  "{chord: {tolerance: 0.0002, max_angle_deg: 4}}" && check decentred decentred_sphere:5:1 0.1 1.0
job eye "{outer_radius: 1.6, inner_radius: 0.03}" \
  "{type: compound_eye, base_radius: 20, lens_radius: -5, lens_diameter: 0.9, pitch: 1.0, pattern: rings}" 0.02 \
  "{equal_angle: {per_rev: 1000}}" && check eye compound_eye:20:-5:0.9:1.0:1.6 0.05 1.6
# lenslets NAME SURFACE NOSE PITCH TOLERANCE DESIGN: a microlens array with h = −0.2 µm, cut
# from 0.01 to 0.45 mm, must plan and its edge stay above the design read back from the NC.
lenslets() {
  cat > "$tmp/$1.yaml" <<YAML
name: $1
aperture: {outer_radius: 0.45, inner_radius: 0.01}
surface: $2
tool: {nose_radius: $3, included_angle_deg: 120, clearance_angle_deg: 40, centre_height: -0.0002}
strategy:
  mode: spiral
  spiral: planar
  pitch: $4
  points: {chord: {tolerance: $5, max_angle_deg: 4}}
cutting: {spindle_rpm: 20}
machine: moore-nanotech-250upl
outputs: {nc: true, report: false}
YAML
  "$freeturn" run "$tmp/$1.yaml" -o "$tmp/$1" --quiet || { echo "FAIL: $1: the run failed"; fail=1; return; }
  local deepest
  deepest=$("$py" "$src/tests/jobs/nc_rake_gouge.py" "$tmp/$1/$1.moore-nanotech-250upl.nc" \
    "$6" "$3" -0.0002 60 0.01 0.45) || { fail=1; return; }
  echo "$1: the edge's deepest below the design: $deepest nm"
  "$py" -c "import sys; sys.exit(0 if float('$deepest') <= 0 else 1)" || { echo "FAIL: $1 cuts into the design"; fail=1; }
}
# Domes with one on the axis (0.29 mm in radius, 0.22 mm across, 0.2357 mm apart), h = −0.2 µm:
# a 0.2 mm nose is held in the 16 µm valleys around the central dome with a touch about
# 0.07 mm from the axis. The reach was taken from a window that reached the axis (β = π/2)
# and the job refused for any h (0.26 mm); the held nose's own touches give 149 nm, and
# with the blocks standing off by it the edge stays 80 nm above the design (with no reach,
# 66 nm into it).
lenslets domes \
  "{type: microlens_array, lens_radius: -0.2908, lens_diameter: 0.2198, pitch: 0.2357, lattice: square}" \
  0.2 0.005 0.0002 microlens_array:-0.2908:0.2198:0.2357:0.45
# Bowls in a hexagonal array with one on the axis (0.148 mm in radius, 0.1371 mm across,
# 0.1965 mm apart), h = −0.2 µm under a 0.1 mm nose and ε = 0.5 µm: each rim a ridge the nose
# rolls over. The window about the central rim reached the axis and the job was refused with
# a reach of 0.2 mm; with β at the ridge it plans (reach 376 nm), and its edge stands 385 nm
# above the design (the array to 0.68 mm planned with no reach at all: 12 nm above it, the
# ridges' effect being of second order in h).
lenslets bowls \
  "{type: microlens_array, lens_radius: 0.148, lens_diameter: 0.1371, pitch: 0.1965, lattice: hexagonal}" \
  0.1 0.01 0.0005 microlens_array:0.148:0.1371:0.1965:0.45:hexagonal
# To the axis with the centre check downgraded: the edge reaches no radius under h, and
# the program is written without those blocks (material left about the axis), its verdict
# UNSAFE (exit 1) with the centre check's finding. It stopped with "X is not a finite
# number" and no file:line:col (exit 2, nothing written) before.
cat > "$tmp/axis.yaml" <<YAML
name: axis
aperture: {outer_radius: 1.0}
surface: {type: compound_eye, base_radius: 20, lens_radius: -5, lens_diameter: 0.9, pitch: 1.0, pattern: rings}
tool: {nose_radius: 0.2, included_angle_deg: 100, clearance_angle_deg: 25, centre_height: 0.002,
       checks: {centre: warning}}
strategy:
  mode: spiral
  spiral: space
  pitch: 0.02
  points: {equal_angle: {per_rev: 400}}
cutting: {spindle_rpm: 10}
machine: moore-nanotech-250upl
outputs: {nc: true, report: true}
YAML
"$freeturn" run "$tmp/axis.yaml" -o "$tmp/axis" --quiet 2> "$tmp/axis.err"
code=$?
if [[ $code != 1 ]]; then
  echo "FAIL: axis: exit $code, expected 1 (UNSAFE)"; cat "$tmp/axis.err"; fail=1
elif ! grep -q "centre: .* (the check is downgraded to a warning in the job)" "$tmp/axis.err"; then
  echo "FAIL: axis: the centre finding is not the reason:"; cat "$tmp/axis.err"; fail=1
else
  deepest=$("$py" "$src/tests/jobs/nc_rake_gouge.py" "$tmp/axis/axis.moore-nanotech-250upl.nc" \
    compound_eye:20:-5:0.9:1.0:1.0 0.2 0.002 50 0 1.0) || fail=1
  echo "axis: the edge's deepest below the design: $deepest nm"
  "$py" -c "import sys; sys.exit(0 if float('$deepest') <= 0 else 1)" || { echo "FAIL: axis cuts into the design"; fail=1; }
fi
# Profile mode on the Precitech (PVT): the part turns under the edge, each edge point cut at
# radius √(x² + h²), between the blocks along the controller's cubics (nc_profile_gouge.py).
cat > "$tmp/profile.yaml" <<YAML
name: profile
aperture: {outer_radius: 2.0, inner_radius: 0.05}
surface: {type: sphere, radius: 3.0}
tool: {nose_radius: 0.2, included_angle_deg: 100, clearance_angle_deg: 25, centre_height: 0.01}
strategy:
  mode: profile
  points: {chord: {tolerance: 0.0001, max_radial_step: 0.2}}
cutting: {feed: 2.0}
machine: precitech-nanoform-250
outputs: {nc: true, report: false}
YAML
# profile_above NAME WHAT: runs $tmp/NAME.yaml and reads its program back: the edge must
# stay above the sphere.
profile_above() {
  local name="$1" what="$2"
  if "$freeturn" run "$tmp/$name.yaml" -o "$tmp/$name" --quiet; then
    deepest=$("$py" "$src/tests/jobs/nc_profile_gouge.py" "$tmp/$name/profile.precitech-nanoform-250.nc" \
      sphere:3.0 0.2 0.01 50 2.0) || fail=1
    echo "$what: the edge's deepest below the design: $deepest nm"
    "$py" -c "import sys; sys.exit(0 if float('$deepest') <= 0 else 1)" || { echo "FAIL: $what cuts into the design"; fail=1; }
  else
    echo "FAIL: $what: the run failed"; fail=1
  fi
}
profile_above profile "profile"
# The same profile to the axis fails the centre check (exit 1, nothing written), and the
# message names the inner radius that holds: |h| = 0.01 mm, where the edge's point on the
# nose's axis reaches √(0² + h²) = h. That radius runs, and reads back above the design.
sed 's/inner_radius: 0.05/inner_radius: 0/' "$tmp/profile.yaml" > "$tmp/profile_axis.yaml"
"$freeturn" run "$tmp/profile_axis.yaml" -o "$tmp/profile_axis" --quiet 2> "$tmp/axis.err"
code=$?
if [[ $code != 1 || -n "$(ls -A "$tmp/profile_axis" 2> /dev/null)" ]]; then
  echo "FAIL: profile to the axis: exit $code, expected 1 and nothing written"; cat "$tmp/axis.err"; fail=1
elif ! grep -qF "centre check: the edge, 10.0000 µm off the spindle line, cannot reach r = " "$tmp/axis.err" ||
     ! grep -qF "set aperture.inner_radius to at least 0.01 mm" "$tmp/axis.err"; then
  echo "FAIL: profile to the axis: the message does not name the inner radius that holds:"; cat "$tmp/axis.err"; fail=1
fi
sed 's/inner_radius: 0.05/inner_radius: 0.01/' "$tmp/profile.yaml" > "$tmp/profile_h.yaml"
profile_above profile_h "profile from r = h, the radius the message names"
exit $fail
