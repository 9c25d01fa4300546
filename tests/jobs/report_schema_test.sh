#!/usr/bin/env bash
# report.json validates against docs/report.schema.json (tests/report/validate_report.py)
# where the example jobs do not reach: a simulated run, an UNSAFE run (the clearance
# check downgraded to a warning), a ring whose troughs are tighter than the nose, a
# constant-rpm run slowed by the machine, a profile with roughing passes, a compensated
# job. And a job whose comment is Latin-1 ("für") is refused
# at its byte.
# The example jobs' own reports are validated by examples_test.sh. Skipped (exit 77)
# without python3-jsonschema.
# usage: report_schema_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
jobs="$src/configs/jobs"
fail=0
"$freeturn" simulate "$jobs/oap_segment.yaml" -o "$tmp/sim" --quiet > /dev/null || { echo "FAIL: simulate"; fail=1; }
# A sphere decentred 0.5 mm: about the axis its flank faces the cut at 14.5°, past the
# tool's 10° clearance, downgraded to a warning.
cat > "$tmp/unsafe.yaml" <<'YAML'
name: cup
aperture: {outer_radius: 0.2}
surface: {type: sphere, radius: 2.0, decenter: {x: 0.5}}
tool: {nose_radius: 0.1, checks: {clearance: warning}}
strategy: {mode: spiral, spiral: planar, pitch: 0.01, points: {chord: {tolerance: 0.001, max_angle_deg: 5}}}
cutting: {spindle_rpm: 20}
machine: iso-lathe-xzc
YAML
"$freeturn" run "$tmp/unsafe.yaml" -o "$tmp/unsafe" --quiet 2> /dev/null
[[ $? == 1 ]] || { echo "FAIL: the unsafe job did not exit 1"; fail=1; }
# The ring's troughs bend to 1/(A ω²) = 0.5066 mm, tighter than a 0.6 mm nose: the nose
# rests on both sides of each, and the report says how much it leaves.
sed -e 's/amplitude: 0.005 /amplitude: 0.05 /' -e 's/period: 2.5 /period: 1.0 /' \
    -e 's/nose_radius: 0.5/nose_radius: 0.6/' "$jobs/sinusoidal_ring.yaml" > "$tmp/held.yaml"
"$freeturn" run "$tmp/held.yaml" -o "$tmp/held" --quiet || { echo "FAIL: the ring held in its troughs"; fail=1; }
sed 's/spindle_rpm: 20/spindle_rpm: 20000\n  timing: constant_rpm/' "$jobs/oap_segment.yaml" > "$tmp/constant.yaml"
(cd "$jobs" && "$freeturn" run "$tmp/constant.yaml" -o "$tmp/constant" --quiet) || { echo "FAIL: constant rpm"; fail=1; }
(cd "$jobs" && "$freeturn" run sinusoidal_ring.yaml -o "$tmp/profile" --quiet) || { echo "FAIL: profile"; fail=1; }
# A compensated job: a sphere measured with 0.2 µm of astigmatism (Z6) in nm, 2 µm piston.
python3 - "$tmp/part1.xyz" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    for i in range(-40, 41):
        for j in range(-40, 41):
            x, y = i * 0.05, j * 0.05
            if math.hypot(x, y) > 2: continue
            r2 = x * x + y * y
            z = r2 / (50 * (1 + math.sqrt(1 - r2 / 2500))) + 0.2e-3 * math.sqrt(6) * (x * x - y * y) / 4 + 2e-3
            f.write(f"{x!r} {y!r} {z * 1e6!r}\n")
PY
cat > "$tmp/plate.yaml" <<'YAML'
name: plate
aperture: {outer_radius: 2.0}
surface: {type: sphere, radius: 50.0}
compensation: {measured: part1.xyz, height_unit: nm, gain: 0.8, register: [piston, tilt], fit: {zernike: 15, bspline: {control_points: 8}}}
tool: {nose_radius: 0.5}
strategy: {mode: spiral, spiral: planar, pitch: 0.05, points: {chord: {tolerance: 0.001, max_angle_deg: 5}}}
cutting: {spindle_rpm: 20}
machine: iso-lathe-xzc
YAML
"$freeturn" run "$tmp/plate.yaml" -o "$tmp/plate" --quiet || { echo "FAIL: the compensated job"; fail=1; }
grep -q 'id="compensation"' "$tmp/plate/plate.report.html" || { echo "FAIL: the page has no compensation table"; fail=1; }
python3 "$src/tests/report/validate_report.py" "$src/docs/report.schema.json" \
  "$tmp/sim/oap_segment.report.json" "$tmp/unsafe/cup.report.json" "$tmp/held/sinusoidal_ring.report.json" \
  "$tmp/constant/oap_segment.report.json" "$tmp/profile/sinusoidal_ring.report.json" \
  "$tmp/plate/plate.report.json"
rc=$?
[[ $rc == 77 ]] && exit 77
[[ $rc == 0 ]] || fail=1
# What each must say, read back: the clearance as an unsafe record with its place; the
# held ring's uncut residual, against the nose placed by brute force; the slowed
# constant-rpm program as a spindle_speed warning, value < limit.
python3 - "$tmp/unsafe/cup.report.json" "$tmp/constant/oap_segment.report.json" "$tmp/held/sinusoidal_ring.report.json" <<'PY' || fail=1
import json, math, sys
unsafe, constant, held = (json.load(open(p, encoding="utf-8")) for p in sys.argv[1:4])
w = [w for w in unsafe["warnings"] if w["kind"] == "clearance"]
assert unsafe["verdict"]["status"] == "UNSAFE", "clearance not UNSAFE"
assert w and w[0]["severity"] == "unsafe" and w[0]["r_mm"] is not None and w[0]["count"] > 0, w
# The flank about the axis: atan(0.5/sqrt(4 - 0.25)) = 14.48 degrees, and more off it.
assert w[0]["value"] >= math.degrees(math.atan(0.5 / math.sqrt(3.75))) - 1e-9 and w[0]["limit"] == 10, w
assert held["verdict"]["status"] == "PASS", held["verdict"]
u = [w for w in held["warnings"] if w["kind"] == "uncut_residual" and w["pass"] == "finish"]
assert u and u[0]["unit"] == "nm", held["warnings"]
# The nose (0.6 mm, placed 0.05 um higher) centred over the axis's fold and each trough
# bottom r_k = 0.75 + k: its centre as high as the section demands, max over rho of
# g(rho) + sqrt(R'^2 - (rho - r_k)^2), sampled every 0.3 um; the material left under it.
A, w_, R, Rp = 0.05, 2 * math.pi, 0.6, 0.6 + 0.5e-4
g = lambda r: A * math.sin(w_ * abs(r))
def left(x):
    n = 4000
    zc = max(g(x + Rp * (2 * i / n - 1)) + math.sqrt(max(Rp * Rp - (Rp * (2 * i / n - 1)) ** 2, 0)) for i in range(n + 1))
    return (zc - R - g(x)) * 1e6
expected = max(left(x) for x in [0.0, 0.75, 1.75, 2.75, 3.75, 4.75])
assert abs(u[0]["value"] - expected) < 1e-3 * expected, (u[0]["value"], expected)
s = [w for w in constant["warnings"] if w["kind"] == "spindle_speed"]
assert s and s[0]["value"] < s[0]["limit"] == 20000 and s[0]["unit"] == "rpm", s
assert constant["timing"]["spindle_rpm"] == s[0]["value"]
PY
# The compensated job's record: astigmatism 200 nm found, the piston, 0.8 of it cut, and
# what is predicted to stay: (1 − 0.8) × 200 nm.
python3 - "$tmp/plate/plate.report.json" <<'PY' || fail=1
import json, sys
c = json.load(open(sys.argv[1], encoding="utf-8"))["compensation"]
assert len(c) == 1, c
c = c[0]
assert abs(c["fit"]["zernike_nm"][5] - 200) < 0.01, c["fit"]
assert abs(c["registration"]["piston_mm"] + 2e-3) < 1e-8, c["registration"]
assert c["fit"]["bspline"]["control_points"] == 8 and c["fit"]["bspline"]["rms_nm"] < 0.01, c["fit"]
assert abs(c["correction_rms_nm"] - 160) < 0.01 and abs(c["predicted_after_rms_nm"] - 40) < 0.01, c
PY
# A Latin-1 byte in a comment: refused at its line and column, exit 2, nothing written.
printf '# f\xfcr die Werkstatt\n' | cat - "$jobs/oap_segment.yaml" > "$tmp/latin1.yaml"
(cd "$jobs" && "$freeturn" run "$tmp/latin1.yaml" -o "$tmp/latin1" --quiet) 2> "$tmp/err"
[[ $? == 2 ]] || { echo "FAIL: a Latin-1 job was not refused with exit 2"; fail=1; }
grep -q "latin1.yaml:1:4: the byte 0xFC is not UTF-8" "$tmp/err" || { echo "FAIL: the Latin-1 byte is not located:"; cat "$tmp/err"; fail=1; }
[[ ! -e "$tmp/latin1" ]] || { echo "FAIL: a refused job left output"; fail=1; }
[[ $fail == 0 ]] && echo "1 passed, 0 failed"
exit $fail
