#!/usr/bin/env bash
# freeturn simulate JOB --program FILE: an NC program read back through the machine's axis
# layout and cut in simulation.
# - freeturn's own program gives the job's own simulated PV within 1 % (the off-axis
#   parabola on the ISO lathe and on the Precitech, whose controller interpolates PVT
#   cubics and whose X runs negative; the Alvarez plate on the Moore B machine, whose
#   program calls a child point file and swings the tool on B about its pivot);
# - the same program with one block moved 1 µm into the part: the worst place is that
#   block's (its X as r within 0.1 mm, its C as θ within 1°), a gouge of about 1 µm;
# - a program that is not NC is an error at its file:line, exit 2, nothing written.
# usage: program_simulation_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
pv() { sed -n 's/.*form error PV \([0-9.]*\) nm.*/\1/p' "$1"; }
sed 's/^machine: .*/machine: precitech-nanoform-250/' "$src/configs/jobs/oap_segment.yaml" > "$tmp/oap_pvt.yaml"
for job in oap_segment alvarez_4axis oap_pvt; do
  file="$src/configs/jobs/$job.yaml"
  [[ $job == oap_pvt ]] && file="$tmp/oap_pvt.yaml"
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
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/moved" --quiet --program "$tmp/moved.nc") > "$tmp/moved.txt" || { echo "FAIL: simulate the moved program"; fail=1; }
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
# Not NC: located, exit 2, nothing written.
printf 'G1 X1 Z0 C0\nG1 X? Z0\n' > "$tmp/bad.nc"
(cd "$src/configs/jobs" && "$freeturn" simulate oap_segment.yaml -o "$tmp/bad" --quiet --program "$tmp/bad.nc") > /dev/null 2> "$tmp/err"
[[ $? == 2 ]] || { echo "FAIL: a bad program did not exit 2"; fail=1; }
grep -q "bad.nc:2:" "$tmp/err" || { echo "FAIL: the bad program's error is not located:"; cat "$tmp/err"; fail=1; }
[[ ! -e "$tmp/bad" || -z "$(ls -A "$tmp/bad")" ]] || { echo "FAIL: a refused program left files"; fail=1; }
[[ $fail == 0 ]] && echo "1 passed, 0 failed"
exit $fail
