#!/usr/bin/env bash
# A rational B-spline design (weights 0.75 to 1.25, uneven knots) cut with chords on a
# Moore, its program read back by tests/jobs/nc_nurbs_gouge.py: the design evaluated there
# by its own Cox-de Boor recursion and (x, y) inversion, the nose swept along the blocks
# as the controller interpolates them. The nose must stay above the design, and come
# within the chord band (tolerance plus stand-off) of it; read with C turned the other
# way, the same check must find the nose microns deep (it can fail).
# usage: nurbs_nc_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Debian's python3 has python3-numpy (scripts/setup.sh); another first on PATH may not.
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
"$py" -c "import numpy" 2> /dev/null || { echo "SKIP: python3 with numpy"; exit 77; }
# The net: 7 × 7 points over x, y ∈ [−5, 5], a saddle-free bowl with a waviness of 30 µm
# and a bump pattern of 10 µm; weights and heights from closed formulas, so the test is
# the same on every machine.
"$py" - "$tmp" <<'PY'
import json, math, sys
tmp = sys.argv[1]
n = 7
points, weights = [], []
for i in range(n):
    for j in range(n):
        x, y = -5 + 10 * i / (n - 1), -5 + 10 * j / (n - 1)
        z = 0.004 * (x * x + 0.6 * y * y) + 0.03 * math.sin(0.7 * x) * math.cos(0.5 * y) \
            + 0.01 * math.sin(3.1 * i + 1.7 * j)
        points.append([x, y, round(z, 6)])
        weights.append(round(1 + 0.25 * math.sin(2.3 * i - 1.1 * j + 0.4), 4))
net = {"degree_u": 3, "degree_v": 3, "knots_u": [0, 0, 0, 0, 0.2, 0.45, 0.7, 1, 1, 1, 1],
       "knots_v": [0, 0, 0, 0, 0.3, 0.5, 0.65, 1, 1, 1, 1], "points": points, "weights": weights}
json.dump(net, open(f"{tmp}/net.json", "w"))
with open(f"{tmp}/job.yaml", "w") as job:
    job.write(f"""name: rational
aperture: {{outer_radius: 2.5}}
surface: {{type: nurbs, degree_u: 3, degree_v: 3, knots_u: {net['knots_u']}, knots_v: {net['knots_v']},
  points: {json.dumps(points)},
  weights: {json.dumps(weights)}}}
tool: {{nose_radius: 0.5, included_angle_deg: 90, clearance_angle_deg: 12}}
strategy:
  mode: spiral
  spiral: planar
  pitch: 0.05
  points: {{chord: {{tolerance: 0.0002, max_angle_deg: 3}}}}
cutting: {{spindle_rpm: 20}}
machine: moore-nanotech-250upl
outputs: {{nc: true, report: true}}
""")
PY
"$freeturn" run "$tmp/job.yaml" -o "$tmp/out" --quiet || { echo "FAIL: the run failed"; exit 1; }
program="$tmp/out/rational.moore-nanotech-250upl.nc"
fail=0
deepest=$("$py" "$src/tests/jobs/nc_nurbs_gouge.py" "$program" "$tmp/net.json" 0.5 45) || exit 1
echo "the nose's deepest below the design: $deepest nm"
# Above the design, and within the band the chord rule keeps it in: the stand-off (100 nm
# for a 200 nm tolerance, the report's) plus the tolerance.
band=$("$py" -c 'import json, sys; p = json.load(open(sys.argv[1]))["parameters"]; print(p["stand_off_nm"] + p["chord_tolerance_nm"])' "$tmp/out/rational.report.json")
"$py" -c "import sys; sys.exit(0 if -$band <= float('$deepest') <= 0 else 1)" ||
  { echo "FAIL: the nose is not within [0, $band] nm above the design at its closest"; fail=1; }
mirrored=$("$py" "$src/tests/jobs/nc_nurbs_gouge.py" "$program" "$tmp/net.json" 0.5 45 -1 10) || exit 1
echo "read with C turned the other way (every tenth block): $mirrored nm"
"$py" -c "import sys; sys.exit(0 if float('$mirrored') > 1000 else 1)" ||
  { echo "FAIL: the check finds no gouge in a program read the wrong way round"; fail=1; }
exit $fail
