#!/usr/bin/env bash
# freeturn simulate JOB --program FILE: an NC program read back through the machine's axis
# layout and cut in simulation.
# - freeturn's own program gives the job's own simulated PV within 1 % (the off-axis
#   parabola on the ISO lathe and on the Precitech, whose controller interpolates PVT
#   cubics and whose X runs negative; the Alvarez plate on the Moore B machine, whose
#   program calls a child point file and swings the tool on B about its pivot);
# - the same with the edge 10 µm above the spindle line (centre_height) and with a
#   measured waviness: the nose centre's angle is C turned by atan2(h, X), and the edge
#   lies R + δ(ψ) from it (simulated as a round nose at C, the first had crashed and read
#   as a gouge of 260 nm); the waviness's simulated cut comes down to the chord rule's
#   stand-off of ε/2 = 50 nm, where the blocks are (a round nose had left 237 nm);
# - the same program with one block moved 1 µm into the part: the worst place is that
#   block's (its X as r within 0.1 mm, its C as θ within 1°), a gouge of about 1 µm, and
#   the verdict is UNSAFE (exit 1): nothing else vouches for a program from elsewhere;
# - a block past the machine's travel: UNSAFE, naming the axis, the limit and the line;
# - blocks after the program's end (M2) are not run, so not cut; a program starting at a
#   negative C (which had crashed the report's turn samples) is simulated;
# - a program that is not NC is an error at its file:line, exit 2, nothing written; so is
#   an axis word given twice in a block;
# - the axes' dynamics from the program's block times: the compound eye's Moore program asks
#   what its run reported; at twice the speed 4x the accelerations, UNSAFE; an inverse-time
#   block with no time (F0, F negative, no F) is UNSAFE at its line.
# usage: program_simulation_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
pv() { sed -n 's/.*form error PV \([0-9.]*\) nm.*/\1/p' "$1"; }
sed 's/^machine: .*/machine: precitech-nanoform-250/' "$src/configs/jobs/oap_segment.yaml" > "$tmp/oap_pvt.yaml"
sed -e 's/^  nose_radius: 0.5$/  nose_radius: 0.5\n  centre_height: 0.01/' -e 's/^  outer_radius: 5.0$/  outer_radius: 5.0\n  inner_radius: 0.5/' \
  "$src/configs/jobs/oap_segment.yaml" > "$tmp/oap_high.yaml"
sed -e 's/^  nose_radius: 0.5$/  nose_radius: 0.5\n  waviness: [[-60, -0.0003], [0, 0.0002], [60, -0.0003]]/' \
  "$src/configs/jobs/oap_segment.yaml" > "$tmp/oap_wavy.yaml"
grep -q centre_height "$tmp/oap_high.yaml" && grep -q waviness "$tmp/oap_wavy.yaml" || { echo "FAIL: the job variants"; fail=1; }
for job in oap_segment alvarez_4axis oap_pvt oap_high oap_wavy; do
  file="$src/configs/jobs/$job.yaml"
  [[ -e $tmp/$job.yaml ]] && file="$tmp/$job.yaml"
  (cd "$src/configs/jobs" && "$freeturn" simulate "$file" -o "$tmp/$job" --quiet) > "$tmp/own.txt" || { echo "FAIL: $job simulate"; fail=1; continue; }
  program=$(ls "$tmp/$job"/*.nc | head -1)
  (cd "$src/configs/jobs" && "$freeturn" simulate "$file" -o "$tmp/$job.program" --quiet --program "$program") > "$tmp/program.txt" ||
    { echo "FAIL: $job simulate --program"; fail=1; continue; }
  a=$(pv "$tmp/own.txt") b=$(pv "$tmp/program.txt")
  if awk -v a="$a" -v b="$b" 'BEGIN { exit !(a > 0 && (b - a) / a < 0.01 && (a - b) / a < 0.01) }'; then
    echo "$job: own simulation PV $a nm, its program read back $b nm"
  else
    echo "FAIL: $job: own simulation PV $a nm, its program read back $b nm (not within 1 %)"; fail=1
  fi
  if [[ $job == oap_wavy ]]; then
    low=$(sed -n 's/.*, min \([-+0-9.]*\) nm at r.*/\1/p' "$tmp/own.txt")
    awk -v m="$low" 'BEGIN { exit !(m >= 0 && m <= 55) }' ||
      { echo "FAIL: $job: the simulated minimum $low nm is not the stand-off 50 nm"; fail=1; }
  fi
  ls "$tmp/$job.program"/*.report.json "$tmp/$job.program"/*.residual.csv > /dev/null 2>&1 || { echo "FAIL: $job: no report or residual"; fail=1; }
done
# One block of the parabola's program 1 µm lower: the block nearest r = 2.5 mm.
python3 - "$tmp/oap_segment/oap_segment.iso-lathe-xzc.nc" "$tmp/moved.nc" > "$tmp/block.txt" <<'PY'
import re, sys
lines = open(sys.argv[1]).read().split("\n")
best, at = 1e9, None
for i, line in enumerate(lines):
    m = re.search(r"X(-?[0-9.]+).*Z(-?[0-9.]+).*C(-?[0-9.]+)", line)
    if m and abs(abs(float(m.group(1))) - 2.5) < best and line.startswith("G1"):
        best, at = abs(abs(float(m.group(1))) - 2.5), i
m = re.search(r"X(-?[0-9.]+).*Z(-?[0-9.]+).*C(-?[0-9.]+)", lines[at])
z = float(m.group(2))
lines[at] = lines[at].replace("Z" + m.group(2), "Z%.6f" % (z - 0.001))
open(sys.argv[2], "w").write("\n".join(lines))
print(abs(float(m.group(1))), float(m.group(3)))
PY
read -r x c < "$tmp/block.txt"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/moved" --quiet --program "$tmp/moved.nc") > "$tmp/moved.txt" 2> "$tmp/moved.err"
[[ $? == 1 ]] || { echo "FAIL: the moved program did not exit 1"; fail=1; }
grep -q "^UNSAFE: the simulated cut goes [0-9.]* nm below the design (the most allowed is 10.0 nm)" "$tmp/moved.err" ||
  { echo "FAIL: the moved program's verdict:"; cat "$tmp/moved.err"; fail=1; }
grep -Eq '"kind": ?"simulated_gouge"' "$tmp/moved"/*.report.json ||
  { echo "FAIL: the moved program's report has no simulated_gouge"; fail=1; }
worst=$(grep -m1 'worst:' "$tmp/moved.txt")
read -r residual r theta < <(echo "$worst" | sed -n 's/.*worst: \([-+0-9.]*\) nm at r = \([0-9.]*\) mm, θ = \([0-9.]*\)°.*/\1 \2 \3/p')
if awk -v e="$residual" -v r="$r" -v t="$theta" -v x="$x" -v c="$c" \
     'BEGIN { c -= 360 * int(c / 360); d = t - c; if (d > 180) d -= 360; if (d < -180) d += 360;
              exit !(e < -500 && r - x < 0.1 && x - r < 0.1 && d < 1 && d > -1) }'; then
  echo "the block moved 1 µm (X $x, C $c) is the worst place: $worst"
else
  echo "FAIL: the moved block (X $x, C $c) is not the worst place: $worst"; fail=1
fi
grep -q "(gouge)" <<< "$worst" || { echo "FAIL: the moved block is not called a gouge"; fail=1; }
# Past the travel: the ISO lathe's X is [-100, 100]; the 40th cutting block at X 120.
nc="$tmp/oap_segment/oap_segment.iso-lathe-xzc.nc"
line=$(grep -n '^G1 X' "$nc" | sed -n 40p | cut -d: -f1)
awk -v n="$line" 'NR == n { sub(/X-?[0-9.]+/, "X120.000000") } { print }' "$nc" > "$tmp/far.nc"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/far" --quiet --program "$tmp/far.nc") > /dev/null 2> "$tmp/far.err"
[[ $? == 1 ]] || { echo "FAIL: a block past the travel did not exit 1"; fail=1; }
grep -q "^UNSAFE: 1 block takes X past its travel limit 100 of machine 'iso-lathe-xzc': X = 120 at .*far.nc:$line\$" "$tmp/far.err" ||
  { echo "FAIL: the travel verdict (line $line):"; cat "$tmp/far.err"; fail=1; }
# After the program's end nothing runs: a plunge 5 mm into the part after M2 cuts nothing.
grep -q '^M2$' "$nc" || { echo "FAIL: the parabola's program has no M2"; fail=1; }
{ cat "$nc"; printf 'G1 X2.5 Z-5 C10\n'; } > "$tmp/after.nc"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/after" --quiet --program "$tmp/after.nc") > "$tmp/after.txt" 2>&1 ||
  { echo "FAIL: a block after M2 was cut:"; cat "$tmp/after.txt"; fail=1; }
cmp -s <(pv "$tmp/after.txt") <(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/again" --quiet --program "$nc" | sed -n 's/.*form error PV \([0-9.]*\) nm.*/\1/p') ||
  { echo "FAIL: a block after M2 changed the simulated PV"; fail=1; }
# A program whose C starts below 0 (the ISO lathe's C accumulates).
printf 'G93\nG1 X2 Z0.6 C-20 F100\nG1 X1.9 Z0.6 C-10 F100\nG1 X1.8 Z0.6 C0 F100\nM2\n' > "$tmp/negative.nc"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/negative" --quiet --program "$tmp/negative.nc") > /dev/null 2>&1
status=$?
[[ $status == 0 || $status == 1 ]] || { echo "FAIL: a program starting at C-20 exited $status"; fail=1; }
# An axis word twice in a block: located, exit 2.
printf 'G1 X1 Z0 C0\nG1 X1 Z0 C4 Z-1\n' > "$tmp/twice.nc"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/twice" --quiet --program "$tmp/twice.nc") > /dev/null 2> "$tmp/err"
[[ $? == 2 ]] || { echo "FAIL: a word twice did not exit 2"; fail=1; }
grep -q "twice.nc:2:13: Z is given twice in one block" "$tmp/err" || { echo "FAIL: the word twice:"; cat "$tmp/err"; fail=1; }
# Axis words under a mode the reading does not follow (G91, inches, cutter compensation, an
# arc's mode), or after a preset of X: located at the word, exit 2, nothing written. Before
# December 2026 each was cut as if absolute millimetres. G91 G28 X0 Z0 then G90 is fine.
for mode in 'G91:3:1' 'G20:3:1' 'G41:3:1' 'G7:3:1' 'G2:3:1' 'G95:3:1' 'G92 X1:2:5'; do
  code=${mode%%:*} where=${mode#*:}
  printf 'G93 G1\n%s\nX2 Z0.6 C0 F100\nX1.9 Z0.6 C10 F100\nM2\n' "$code" > "$tmp/mode.nc"
  rm -rf "$tmp/mode"
  (cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/mode" --quiet --program "$tmp/mode.nc") > /dev/null 2> "$tmp/err"
  [[ $? == 2 ]] || { echo "FAIL: $code in the program did not exit 2"; fail=1; }
  grep -q "mode.nc:$where: " "$tmp/err" || { echo "FAIL: $code is not located at $where:"; cat "$tmp/err"; fail=1; }
  [[ ! -e "$tmp/mode" || -z "$(ls -A "$tmp/mode")" ]] || { echo "FAIL: $code left files"; fail=1; }
done
printf 'G91 G28 X0 Z0\nG90 G93 G21\nG1 X2 Z0.6 C0 F100\nG1 X1.9 Z0.6 C10 F100\nM2\n' > "$tmp/idiom.nc"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/idiom" --quiet --program "$tmp/idiom.nc") > /dev/null 2> "$tmp/err"
status=$?
[[ $status == 0 || $status == 1 ]] || { echo "FAIL: G91 G28 X0 Z0 then G90 was refused:"; cat "$tmp/err"; fail=1; }
# Not NC: located, exit 2, nothing written.
printf 'G1 X1 Z0 C0\nG1 X? Z0\n' > "$tmp/bad.nc"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/bad" --quiet --program "$tmp/bad.nc") > /dev/null 2> "$tmp/err"
[[ $? == 2 ]] || { echo "FAIL: a bad program did not exit 2"; fail=1; }
grep -q "bad.nc:2:" "$tmp/err" || { echo "FAIL: the bad program's error is not located:"; cat "$tmp/err"; fail=1; }
[[ ! -e "$tmp/bad" || -z "$(ls -A "$tmp/bad")" ]] || { echo "FAIL: a refused program left files"; fail=1; }
# The axes' dynamics from the program's own block times (Moore: G93 F in seconds): the
# compound eye's program read back asks what its run reported, within the words' rounding
# (1 %); with every F halved each block takes half the time, so every acceleration is 4×
# (velocity 2× over half the time): X's peak then breaks the 500 mm/s² limit, UNSAFE.
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
(cd "$src/configs/jobs" && "$freeturn" run compound_eye.yaml -o "$tmp/eye" --quiet) || { echo "FAIL: the compound eye's run"; fail=1; }
(cd "$src/configs/jobs" && "$freeturn" simulate compound_eye.yaml -o "$tmp/eye.program" --quiet \
  --program "$tmp/eye/compound_eye.moore-nanotech-250upl.nc") > /dev/null 2> "$tmp/eye.err" ||
  { echo "FAIL: the compound eye's own program is not safe read back:"; cat "$tmp/eye.err"; fail=1; }
mkdir -p "$tmp/fast"
cp "$tmp/eye"/*.nc "$tmp/fast/"
"$py" - "$tmp/fast/compound_eye_001.nc" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
open(sys.argv[1], "w").write(re.sub(r"F([0-9.]+)", lambda m: "F%.6f" % (float(m.group(1)) / 2), text))
PY
(cd "$src/configs/jobs" && "$freeturn" simulate compound_eye.yaml -o "$tmp/fast.program" --quiet \
  --program "$tmp/fast/compound_eye.moore-nanotech-250upl.nc") > /dev/null 2> "$tmp/fast.err"
[[ $? == 1 ]] || { echo "FAIL: the program at twice the speed did not exit 1"; fail=1; }
grep -q "^UNSAFE: [0-9]* blocks ask X acceleration beyond machine 'moore-nanotech-250upl'" "$tmp/fast.err" ||
  { echo "FAIL: the fast program's verdict:"; cat "$tmp/fast.err"; fail=1; }
"$py" - "$tmp/eye/compound_eye.report.json" "$tmp/eye.program/compound_eye.report.json" \
  "$tmp/fast.program/compound_eye.report.json" <<'PY' || fail=1
import json, sys
run, back, fast = (json.load(open(p))["passes"][-1] for p in sys.argv[1:4])
ok = True
for axis in "XZC":
    a, b, c = (p["peak_acceleration_per_s2"][axis] for p in (run, back, fast))
    print("%s acceleration: the run %.4g, read back %.4g, at twice the speed %.4g (%.3f x)" % (axis, a, b, c, c / b))
    if abs(b / a - 1) > 0.01 or abs(c / b / 4 - 1) > 0.02:
        print("FAIL: %s acceleration not as the run's, or not 4x at twice the speed" % axis)
        ok = False
if abs(back["cycle_time_s"] / run["cycle_time_s"] - 1) > 1e-6 or abs(fast["cycle_time_s"] / back["cycle_time_s"] - 0.5) > 1e-3:
    print("FAIL: the cycle times", run["cycle_time_s"], back["cycle_time_s"], fast["cycle_time_s"])
    ok = False
sys.exit(0 if ok else 1)
PY
# Two passes in one program (LinuxCNC: G93 F is 1/minutes): the second, after a retract,
# is judged from rest too; its blocks of 1/240000 min (0.25 ms) come at 4 000 a second,
# past the ISO lathe's 1 000.
{
  printf 'G93\n'
  for k in 0 1 2 3 4; do printf 'G1 X%s Z0.56 C%d F2400\n' "$(awk -v k=$k 'BEGIN { print 2 - k * 0.001 }')" $((k * 3)); done
  printf 'G94\nG0 Z2\nG0 X2 C0\nG1 Z0.56 F20\nG93\n'
  for k in 0 1 2 3 4; do printf 'G1 X%s Z0.56 C%d F240000\n' "$(awk -v k=$k 'BEGIN { print 2 - k * 0.00001 }')" $((k * 3)); done
  printf 'G94\nG0 Z2\nM2\n'
} > "$tmp/passes.nc"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/passes" --quiet --program "$tmp/passes.nc") > /dev/null 2> "$tmp/passes.err"
[[ $? == 1 ]] || { echo "FAIL: the second pass's block rate did not make it UNSAFE"; fail=1; }
grep -q "^UNSAFE: 5 blocks ask a block rate beyond machine 'iso-lathe-xzc': 4000 blocks/s against 1000 at .*passes.nc:1[2-6]$" "$tmp/passes.err" ||
  { echo "FAIL: the second pass's verdict:"; cat "$tmp/passes.err"; fail=1; }
# The first pass, at 40 blocks a second from a program whose first block is its start, asks
# nothing past the limits.
[[ $(grep -c '^UNSAFE' "$tmp/passes.err") -le 3 ]] && ! grep -q 'passes.nc:[2-6]$' "$tmp/passes.err" ||
  { echo "FAIL: the first pass was judged past a limit:"; cat "$tmp/passes.err"; fail=1; }
# A cut that ends fast: C turns 120 °/s through every block, the last a tenth as long
# (0.3° in 2.5 ms), and the run stops after it: 120 / 0.0025 = 48 000 °/s² against the
# ISO lathe's 36 000, though no block changes speed (before, such a stop was not judged).
{
  printf 'G93\n'
  for k in 0 1 2 3; do printf 'G1 X2 Z0.56 C%d F2400\n' $((k * 3)); done
  printf 'G1 X2 Z0.56 C9.3 F24000\nG94\nG0 Z2\nM2\n'
} > "$tmp/stop.nc"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/stop" --quiet --program "$tmp/stop.nc") > /dev/null 2> "$tmp/stop.err"
[[ $? == 1 ]] || { echo "FAIL: the hard stop did not make it UNSAFE"; fail=1; }
grep -q "^UNSAFE: 1 block asks C acceleration beyond machine 'iso-lathe-xzc': 4.8e+04 deg/s2 against 3.6e+04 at .*stop.nc:6$" "$tmp/stop.err" ||
  { echo "FAIL: the hard stop's verdict:"; cat "$tmp/stop.err"; fail=1; }
# An inverse-time block with no time: F0, a negative F, or no F at all under G93. A controller
# refuses such a block (before, the dynamics were only noted as not judged, in a sentence
# that said the opposite: "states a time this reader knows").
for f in "F0" "F-0.5" ""; do
  { printf 'G93\nG1 X2 Z0.56 C0 F2400\nG1 X1.999 Z0.56 C3 F2400\n'; printf 'G1 X1.998 Z0.56 C6 %s\nM2\n' "$f"; } > "$tmp/no_time.nc"
  # Without an F on the first block either: none has a time.
  [[ -z $f ]] && printf 'G93\nG1 X2 Z0.56 C0\nG1 X1.999 Z0.56 C3\nM2\n' > "$tmp/no_time.nc"
  (cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/no_time" --quiet --program "$tmp/no_time.nc") > /dev/null 2> "$tmp/no_time.err"
  [[ $? == 1 ]] || { echo "FAIL: G93 with '$f' did not exit 1"; fail=1; }
  want="^UNSAFE: the inverse-time (G93) block at .*no_time.nc:4 states $f: no block time"
  [[ -z $f ]] && want="^UNSAFE: the inverse-time (G93) block at .*no_time.nc:2 states no F: no block time"
  grep -q "$want" "$tmp/no_time.err" || { echo "FAIL: G93 with '$f':"; cat "$tmp/no_time.err"; fail=1; }
done
[[ $fail == 0 ]] && echo "1 passed, 0 failed"
exit $fail
