#!/usr/bin/env bash
# The iso post's programs pass LinuxCNC's own interpreter (rs274 from Debian's
# linuxcnc-uspace), for the X-Z-C and X-Z-C-B machines: exit 0 and one STRAIGHT_FEED per
# G1 block. Skipped (exit 77) where rs274 is absent; CI installs it (.ci/run).
# usage: linuxcnc_test.sh <write_iso_program> <plugin dir> <machine dir>
set -u
writer=$1 plugins=$2 machines=$3
command -v rs274 > /dev/null || { echo "rs274 not installed (apt-get install linuxcnc-uspace): skipped"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
for spec in "xzc:XZC:3" "xzcb:XZBC:4"; do
  IFS=: read -r name coordinates joints <<< "$spec"
  cat > "$tmp/$name.ini" <<INI
[EMC]
VERSION = 1.1
[RS274NGC]
PARAMETER_FILE = $tmp/sim.var
[TRAJ]
COORDINATES = $coordinates
LINEAR_UNITS = mm
ANGULAR_UNITS = degree
[KINS]
KINEMATICS = trivkins coordinates=$coordinates
JOINTS = $joints
[DISPLAY]
LATHE = 1
INI
  touch "$tmp/sim.var"
  "$writer" "$plugins/libfreeturn_post_iso.so" "$machines/iso-lathe-$name.yaml" "$tmp/$name.ngc" || {
    echo "FAIL: writing the $name program"; fail=1; continue; }
  (cd "$tmp" && rs274 -i "$name.ini" -g "$name.ngc" "$name.txt" > "$name.log" 2>&1)
  rc=$?
  g1=$(grep -c '^G1 ' "$tmp/$name.ngc")
  feeds=$(grep -c 'STRAIGHT_FEED' "$tmp/$name.txt")
  if [[ $rc != 0 ]]; then
    echo "FAIL: rs274 rejected the $name program (exit $rc):"; tail -5 "$tmp/$name.log" "$tmp/$name.txt"; fail=1
  elif [[ $g1 != "$feeds" ]]; then
    echo "FAIL: $name: $g1 G1 blocks but $feeds STRAIGHT_FEED calls"; fail=1
  else
    echo "ok: $name program, $g1 G1 blocks, all interpreted"
  fi
done
[[ $fail == 0 ]] && echo "2 passed, 0 failed"
exit $fail
