#!/usr/bin/env bash
# report.json validates against docs/report.schema.json (tests/report/validate_report.py)
# where the example jobs do not reach: a simulated run, an UNSAFE run (a gouge check
# downgraded to a warning), a constant-rpm run slowed by the machine, a profile with
# roughing passes, a compensated job. And a job whose comment is Latin-1 ("für") is refused
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
sed -e 's/amplitude: 0.005 /amplitude: 0.05 /' -e 's/period: 2.5 /period: 1.0 /' \
    -e 's/nose_radius: 0.5/nose_radius: 0.6\n  checks: {gouge: warning, global_gouge: warning}/' \
    "$jobs/sinusoidal_ring.yaml" > "$tmp/gouge.yaml"
"$freeturn" run "$tmp/gouge.yaml" -o "$tmp/gouge" --quiet 2> /dev/null
[[ $? == 1 ]] || { echo "FAIL: the gouging job did not exit 1"; fail=1; }
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
  "$tmp/sim/oap_segment.report.json" "$tmp/gouge/sinusoidal_ring.report.json" \
  "$tmp/constant/oap_segment.report.json" "$tmp/profile/sinusoidal_ring.report.json" \
  "$tmp/plate/plate.report.json"
rc=$?
[[ $rc == 77 ]] && exit 77
[[ $rc == 0 ]] || fail=1
# What each must say, read back: the gouge as an unsafe local_gouge record with its place;
# the slowed constant-rpm program as a spindle_speed warning, value < limit.
python3 - "$tmp/gouge/sinusoidal_ring.report.json" "$tmp/constant/oap_segment.report.json" <<'PY' || fail=1
import json, sys
gouge, constant = (json.load(open(p, encoding="utf-8")) for p in sys.argv[1:3])
w = [w for w in gouge["warnings"] if w["kind"] == "local_gouge"]
assert gouge["verdict"]["status"] == "UNSAFE", "gouge not UNSAFE"
assert w and w[0]["severity"] == "unsafe" and w[0]["r_mm"] is not None and w[0]["count"] > 0, w
# The trough's concave radius 1/(A ω²), ω = 2π/1.0, A = 0.05: 0.5066 mm, against the 0.6 mm nose.
assert abs(w[0]["value"] - 1 / (0.05 * (2 * 3.141592653589793) ** 2)) < 0.01 and w[0]["limit"] == 0.6, w
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
