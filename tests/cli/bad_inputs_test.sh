#!/usr/bin/env bash
# Bad inputs a user (or an attacker) writes: each is refused with exit 2, a message at
# file:line:col naming what is wrong, nothing in the output folder, in under 5 s.
set -uo pipefail
freeturn="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
fail=0
cases=0

# refused DESCRIPTION FILE EXPECTED-PREFIX WORDS...: `freeturn check` and `run` on the job
# FILE exit 2, stderr starts with EXPECTED-PREFIX (file:line:col) and holds every WORD.
refused() {
  local what="$1" job="$2" where="$3"
  shift 3
  cases=$((cases + 1))
  for command in check run; do
    rm -rf "$tmp/out"
    mkdir -p "$tmp/out"
    local start=$SECONDS
    local args=("$job")
    [[ "$command" == run ]] && args+=(-o "$tmp/out")
    (cd "$tmp/out" && timeout 20 "$freeturn" "$command" "${args[@]}" > "$tmp/stdout" 2> "$tmp/err")
    local code=$?
    local took=$((SECONDS - start))
    if [[ "$code" != 2 ]]; then echo "FAIL: $what ($command): exit $code, expected 2"; cat "$tmp/err"; fail=1; continue; fi
    if [[ "$(head -c ${#where} "$tmp/err")" != "$where" ]]; then
      echo "FAIL: $what ($command): stderr does not start with '$where':"; cat "$tmp/err"; fail=1
    fi
    for word in "$@"; do
      grep -qF -- "$word" "$tmp/err" || { echo "FAIL: $what ($command): '$word' not in:"; cat "$tmp/err"; fail=1; }
    done
    if [[ -n "$(ls -A "$tmp/out")" ]]; then echo "FAIL: $what ($command): left $(ls -A "$tmp/out")"; fail=1; fi
    if ((took > 5)); then echo "FAIL: $what ($command): took ${took} s"; fail=1; fi
  done
}

# A small valid job to break one line at a time (LinuxCNC lathe, X Z C, ISO dialect).
base="$tmp/base.yaml"
cat > "$base" <<'YAML'
name: plate
aperture:
  outer_radius: 2.0
surface:
  type: sphere
  radius: 50.0
tool:
  nose_radius: 0.5
  clearance_angle_deg: 10
strategy:
  mode: spiral
  spiral: planar
  pitch: 0.05
  points:
    chord: {tolerance: 0.001, max_angle_deg: 5}
cutting:
  spindle_rpm: 20
machine: MACHINE
YAML
cp "$src/postprocessors/iso/machines/iso-lathe-xzc.yaml" "$tmp/machine.yaml"
sed -i "s|MACHINE|$tmp/machine.yaml|" "$base"
"$freeturn" check "$base" > /dev/null 2>&1 || { echo "FAIL: the base job does not pass"; "$freeturn" check "$base"; exit 1; }

# variant NAME SED-SCRIPT: the base job edited.
variant() { sed "$2" "$base" > "$tmp/$1.yaml"; echo "$tmp/$1.yaml"; }

# A ring narrower than the pitch: the spiral would turn 0.0002 of a revolution over it.
job=$(variant narrow_ring 's/^  outer_radius: 2.0/  outer_radius: 2.0\n  inner_radius: 1.99999/')
refused "a ring narrower than the pitch" "$job" "$job:14:10:" "strategy.pitch 0.05 mm is wider than the aperture's ring (1e-05 mm" "turn 0.0002 of a revolution"

# A ring whose troughs bend to 1/(A ω²) = 1/(0.5 (2π/0.01)²) = 5.066 nm, under the stand-off
# of half the 1 µm tolerance: no nose radius follows them, and none is suggested (the
# message once said "use a nose radius under -0.000495 mm"). The radius it names is the
# tightest of its samples across the nose: no tighter than the troughs' own, and under the
# stand-off. (Its 10 µm period is a third of the steps a trough tighter than the nose is
# looked for at, docs/tool.md: the planner stops where it finds none.)
job=$(variant sharp_ring 's/type: sphere/type: sinusoidal_ring\n  amplitude: 0.5\n  period: 0.01/; /radius: 50.0/d')
refused "troughs tighter than the stand-off" "$job" "$job:16:24:" "concave radius of " "no nose radius does: the stand-off of 0.5 µm"
if grep -qF "under -" "$tmp/err"; then echo "FAIL: troughs tighter than the stand-off: a negative nose radius is suggested"; fail=1; fi
named=$(sed -n 's/.*concave radius of \([0-9.e+-]*\) mm.*/\1/p' "$tmp/err")
awk -v r="$named" 'BEGIN { exit !(r >= 5.066e-06 && r < 0.5e-3) }' || { echo "FAIL: troughs tighter than the stand-off: the radius named, '$named' mm, is not between 5.066e-06 and the stand-off"; fail=1; }

# Lenslets 6 µm apart under the 0.5 mm nose: a section meets about 330 rims under it, more
# than its envelope follows (docs/tool.md, "Sections that meet more creases than a list
# holds"). Refused before planning: found after the revolutions outside, it took minutes.
job=$(variant fine_lenslets 's/type: sphere/type: microlens_array\n  lens_radius: -0.6\n  lens_diameter: 0.0054\n  pitch: 0.006/; /radius: 50.0/d')
refused "lenslets finer than the nose's envelope follows" "$job" "$job:10:16:" "tool.nose_radius" "more than 256 creases" "use a nose radius that spans fewer"

# YAML that a person would not mean.
job=$(variant dup_key 's/^  pitch: 0.05/  pitch: 0.05\n  pitch: 0.5/')
refused "a duplicate key" "$job" "$job:14:3:" "'pitch' appears twice"
job=$(variant dup_flow 's/chord: {tolerance: 0.001, max_angle_deg: 5}/chord: {tolerance: 0.001, tolerance: 0.01}/')
refused "a duplicate key in a flow map" "$job" "$job:15:31:" "'tolerance' appears twice"
job=$(variant dup_machine "s|^machine: .*|&\nmachine: iso-lathe-xz|")
refused "machine twice" "$job" "$job:19:1:" "'machine' appears twice"
job=$(variant two_docs '$a ---\nname: other')
refused "a second document" "$job" "$job:19:1:" "second YAML document"
job=$(variant open_quote 's/^name: plate/name: "plate/')
refused "an unterminated quote" "$job" "$job:1:7:" "does not close on its line"
job=$(variant bom_mid 's/^tool:/\xef\xbb\xbftool:/')
refused "a byte-order mark mid-file" "$job" "$job:7:1:" "byte-order mark"
# Aliases of aliases (a "billion laughs"): 600 bytes that stand for 9^13 values.
cp "$base" "$tmp/aliases.yaml"
echo 'l0: &l0 [x, x, x, x, x, x, x, x, x]' >> "$tmp/aliases.yaml"
for k in $(seq 1 12); do
  echo "l$k: &l$k [*l$((k - 1)), *l$((k - 1)), *l$((k - 1)), *l$((k - 1)), *l$((k - 1)), *l$((k - 1)), *l$((k - 1)), *l$((k - 1)), *l$((k - 1))]" >> "$tmp/aliases.yaml"
done
refused "aliases of aliases" "$tmp/aliases.yaml" "$tmp/aliases.yaml:19:" "aliases ('*name')"
# 100 000 brackets deep: yaml-cpp's own depth bound stops it (its message says "bad file").
{ printf 'name: plate\nsurface: '; head -c 100000 /dev/zero | tr '\0' '['; head -c 100000 /dev/zero | tr '\0' ']'; echo; } > "$tmp/deep.yaml"
refused "brackets 100 000 deep" "$tmp/deep.yaml" "$tmp/deep.yaml:2:" "nested more than 64 levels deep"
# A right-to-left override in a name would make the message read as another name.
job=$(variant bidi 's/^name: plate/name: "pl\\u202eate"/')
refused "a right-to-left override in the name" "$job" "$job:1:7:" "'pl\\u202eate'"
printf 'name: plate\0\n' > "$tmp/nul.yaml"
refused "a NUL byte" "$tmp/nul.yaml" "$tmp/nul.yaml:1:12:" "control character"
# A scalar carrying a terminal escape and a NUL (YAML's "\e" and "\0"): the message
# quotes it with the bytes written as \xNN, so none reaches the terminal.
job=$(variant escape_seq 's/type: sphere/type: "sph\\e[2J\\0ere"/')
refused "a terminal escape in a scalar" "$job" "$job:5:9:" "'sph\x1b[2J\x00ere'"
if LC_ALL=C grep -q '[[:cntrl:]]' <(tr -d '\n' < "$tmp/err"); then
  echo "FAIL: a terminal escape in a scalar: a control byte reached stderr"; fail=1
fi
mkdir -p "$tmp/dir.yaml"
refused "a directory as the job" "$tmp/dir.yaml" "$tmp/dir.yaml:" "is a directory"
refused "a device as the job" /dev/zero "/dev/zero:" "not a regular file"
head -c 5000000 /dev/zero | tr '\0' '#' > "$tmp/huge.yaml"
refused "a 5 MB job" "$tmp/huge.yaml" "$tmp/huge.yaml:" "over the 4194304-byte bound"

# A key with nothing after it: yaml-cpp marks the empty value at the next line's key.
job=$(variant empty_value 's/^  radius: 50.0/  radius:/')
refused "a key with no value" "$job" "$job:6:3:" "surface.radius has no value"

# Ranges the schema states.
job=$(variant clearance 's/clearance_angle_deg: 10/clearance_angle_deg: 720/')
refused "clearance 720°" "$job" "$job:9:24:" "clearance_angle_deg must be within (0, 45]"
job=$(variant rpm_tiny 's/spindle_rpm: 20/spindle_rpm: 1e-9/')
refused "a spindle of 1e-9 rpm (S0.000)" "$job" "$job:17:16:" "spindle_rpm must be within [0.001, 20000] rpm"
job=$(variant pitch 's/pitch: 0.05/pitch: 1.5/')
refused "a pitch of three nose radii" "$job" "$job:13:10:" "would not overlap"
job=$(variant tolerance 's/tolerance: 0.001/tolerance: 1e-30/')
refused "a chord tolerance of 1e-30" "$job" "$job:15:24:" "tolerance must be within"
job=$(variant angle 's/max_angle_deg: 5/max_angle_deg: 1e-9/')
refused "max_angle_deg 1e-9" "$job" "$job:15:46:" "max_angle_deg must be within"
job=$(variant arc 's/chord: {tolerance: 0.001, max_angle_deg: 5}/equal_arc: {length: 1e-12}/')
refused "an arc step of 1e-12 mm" "$job" "$job:15:25:" "length must be within"
job=$(variant arc_many 's/chord: {tolerance: 0.001, max_angle_deg: 5}/equal_arc: {length: 1e-5}/')
echo "limits: {max_points: 1000000}" >> "$job"
refused "an arc step over the point limit" "$job" "$job:15:25:" "limits.max_points"
# A profile's feed beyond an axis' velocity (the X-Z lathe: 50 mm/s, 3000 mm/min): it had
# been written as F6000 and passed.
sed -e 's/^  mode: spiral/  mode: profile/' -e '/^  spiral: planar/d' -e '/^  pitch: 0.05/d' \
  -e 's/chord: {tolerance: 0.001, max_angle_deg: 5}/chord: {tolerance: 0.001}/' \
  -e 's/^  spindle_rpm: 20/  feed: 6000/' -e 's/^machine: .*/machine: iso-lathe-xz/' "$base" > "$tmp/fast_feed.yaml"
refused "a profile feed beyond X's velocity" "$tmp/fast_feed.yaml" "$tmp/fast_feed.yaml:15:9:" "cutting.feed 6000 mm/min moves X at up to 100 mm/s, beyond the max_velocity 50 mm/s"
# A pitch typo: the turns alone, at 3 points each, pass the limit. Named at the pitch, not
# at the points' rule (which it had been).
job=$(variant pitch_tiny 's/pitch: 0.05/pitch: 1e-300/')
refused "a pitch of 1e-300 mm" "$job" "$job:13:10:" "strategy.pitch makes 2e+300 revolutions, which at 3 points each"

job=$(variant rpm 's/spindle_rpm: 20/spindle_rpm: 1e9/')
refused "1e9 rpm" "$job" "$job:17:16:" "spindle_rpm must be within [0.001, 20000]"
job=$(variant long_name "s/^name: plate/name: $(printf 'n%.0s' {1..300})/")
refused "a 300-character name" "$job" "$job:1:7:" "at most 100"
job=$(variant waviness 's/^  clearance_angle_deg: 10/&\n  waviness: [[0, 0.6]]/')
refused "a waviness larger than the nose" "$job" "$job:10:18:" "smaller than a tenth of the nose radius"
job=$(variant flipped 's/^  radius: 50.0/&\n  tilt_deg: {x: 120}/')
refused "a tilt that turns the part away from the tool" "$job" "$job:7:13:" "turns the surface 120° from the spindle axis"
# On a creased design (a cone's vertex) the chord band must hold the waviness's span.
job=$(variant wavy_cone 's/^  type: sphere/  type: odd_asphere\n  coefficients: [0.01]/; s/^  clearance_angle_deg: 10/&\n  waviness: [[-30, 0.0005], [30, -0.0005]]/')
refused "a waviness spanning the chord tolerance on a creased design" "$job" "$job:11:13:" "tool.waviness lets the edge reach 1000 nm past the round nose" "give a chord tolerance above 1111 nm"
# A smooth bowl the 0.5 mm nose nearly fits (R 0.5002 mm): the nose clears it only by
# R(1 − κR)Δφ²/2 away from its touch, less than the edge's waviness rises there, so the
# edge reaches its whole span (250 nm over ±30°) past the round nose. It had passed, and
# such a job cut 53 nm into its bowl (NC-only check).
job=$(variant nearfit 's/outer_radius: 2.0/outer_radius: 0.2/; s/radius: 50.0/radius: 0.5002/; s/tolerance: 0.001,/tolerance: 0.0002,/; s/^  clearance_angle_deg: 10/&\n  waviness: [[-60, -0.0003], [0, 0.0002], [60, -0.0003]]/')
refused "a waviness a nearly fitting nose carries past the chord band" "$job" "$job:10:13:" "lets the edge reach 250 nm past the round nose" "give a chord tolerance above 277.8 nm"

# The edge lies in the rake plane h above the spindle line: a nose held at a lenslet rim
# touches the far flank across the radial plane the chords are measured in (docs/tool.md,
# "Centre height"). 0.2 mm of it there leaves the 1 µm chords no band.
job=$(variant eye_high 's/^  type: sphere/  type: compound_eye\n  base_radius: 20.0\n  lens_radius: -5.0\n  lens_diameter: 0.9\n  pitch: 1.0\n  pattern: rings/; /^  radius: 50.0/d; s/^  outer_radius: 2.0/&\n  inner_radius: 0.3/; s/^  clearance_angle_deg: 10/&\n  centre_height: 0.2/')
refused "a centre height that moves a held nose's far touch past the chord band" "$job" "$job:15:18:" "tool.centre_height lets the edge, which lies in the rake plane" "or measure the centre height smaller"

# Errors found after reading, at the key that causes them.
job=$(variant xz "s|^machine: .*|machine: iso-lathe-xz|")
refused "a spiral on an X-Z machine" "$job" "$job:18:10:" "needs a C axis"
job=$(variant follow 's/^strategy:/strategy:\n  b_axis: follow/')
refused "B following on a 3-axis machine" "$job" "$job:11:11:" "needs a B axis"
job=$(variant profile 's/mode: spiral/mode: profile/; s/spindle_rpm: 20/feed: 10/; /^  spiral: planar/d; /^  pitch: 0.05/d; s/^  radius: 50.0/&\n  decenter: {x: 3}/')
refused "profile mode on a surface that is not revolved" "$job" "$job:12:9:" "not rotationally symmetric"
job=$(variant no_machine "s|^machine: .*|machine: no-such-lathe|")
refused "a missing machine" "$job" "$job:18:10:" "no no-such-lathe.yaml"

# Machine and dialect settings.
machine_variant() {  # NAME SED-SCRIPT [MACHINE-FILE, the ISO lathe's by default]
  sed "$2" "${3:-$tmp/machine.yaml}" > "$tmp/$1.machine.yaml"
  sed "s|^machine: .*|machine: $tmp/$1.machine.yaml|" "$base" > "$tmp/$1.yaml"
  echo "$tmp/$1"
}
# Z words rounded to 1 µm round a block by more than half the 500 nm stand-off the chord
# rule gives it (decimals: 0 had written X2 for X1.97998, and passed).
m=$(machine_variant coarse_z 's/\({name: Z, sign: 1, min: [^,]*, max: [^,]*, decimals: \)6/\13/')
refused "Z words too coarse for the tolerance" "$m.yaml" "$m.machine.yaml:6:53:" "machine axis Z decimals 3" "round the nose's position by up to 500.7 nm"
# Z at 5 decimals rounds a block by 5 nm, more than the 5 nm equal angles allow where their
# blocks sit on the design (with X's and C's 0.7 nm: 5.67 nm); the chord rule's stand-off
# would take 10 nm, and the refusal says so (it said only "write more decimals", which a
# controller's resolution may not allow). With the base job's chords the same file runs.
m=$(machine_variant coarse_z5 's/\({name: Z, sign: 1, min: [^,]*, max: [^,]*, decimals: \)6/\15/')
sed -i 's/chord: {tolerance: 0.001, max_angle_deg: 5}/equal_angle: {per_rev: 90}/' "$m.yaml"
refused "Z words too coarse for equal angles" "$m.yaml" "$m.machine.yaml:6:53:" "machine axis Z decimals 5" \
  "or place the points by the chord rule (strategy.points.chord)" "up to 10 nm"
sed -i 's/equal_angle: {per_rev: 90}/chord: {tolerance: 0.001, max_angle_deg: 5}/' "$m.yaml"
"$freeturn" check "$m.yaml" > /dev/null 2>&1 || { echo "FAIL: Z at 5 decimals with the chord rule: check failed"; "$freeturn" check "$m.yaml"; fail=1; }
m=$(machine_variant retract 's/^  retract: .*/  retract: -1.46/')
refused "a negative retract" "$m.yaml" "$m.machine.yaml:12:12:" "'retract' is -1.46, outside"
m=$(machine_variant feed 's/^  approach_feed: .*/  approach_feed: 1e300/')
refused "an approach feed of 1e300" "$m.yaml" "$m.machine.yaml:13:18:" "'approach_feed' is 1e300"
m=$(machine_variant dialect_dup 's/^  retract: .*/  retract: 1\n  retract: 2/')
refused "a dialect key twice" "$m.yaml" "$m.machine.yaml:13:3:" "'retract' appears twice"

m=$(machine_variant unknown_setting 's/^  retract: .*/&\n  colour: red/')
refused "an unknown dialect key" "$m.yaml" "$m.machine.yaml:13:3:" "unknown setting 'colour'"
m=$(machine_variant z_travel 's/min: -50, max: 50, decimals: 6/min: -50, max: 1.2, decimals: 6/')
refused "an approach height beyond the Z travel" "$m.yaml" "$m.machine.yaml:6:39:" "machine axis Z max" "Z1.54"
# Dynamic limits so small they are typos: the scheduler would write blocks decades long.
m=$(machine_variant slow_x 's/max: 100, decimals: 6, max_velocity: 50,/max: 100, decimals: 6, max_velocity: 1e-12,/')
refused "an X velocity limit of 1e-12 mm/s" "$m.yaml" "$m.machine.yaml:5:72:" "max_velocity must be at least 0.001 mm/s, not 1e-12"
m=$(machine_variant slow_blocks 's/^max_block_rate: 1000/max_block_rate: 1e-9/')
refused "a block rate of 1e-9" "$m.yaml" "$m.machine.yaml:10:17:" "max_block_rate must be at least 1 blocks/s"
# The machine's name names the program file: a path in it would write outside the folder.
m=$(machine_variant name_path 's/^name: .*/name: "..\/..\/evil"/')
refused "a machine name that is a path" "$m.yaml" "$m.machine.yaml:2:7:" "machine name '../../evil' must use only letters"
m=$(machine_variant plugin_path 's/^plugin: iso/plugin: ..\/iso/')
refused "a plugin path with .." "$m.yaml" "$m.machine.yaml:3:9:" "a name, not a path"

# A Moore header that ends the program before the cut: a '%' line after the first (the
# tape's end to an RS-274 reader) or an M30. Reported at the header in the machine file.
moore="$src/postprocessors/moore/machines/moore-nanotech-250upl.yaml"
m=$(machine_variant tape_end 's/^  header: "G71/  header: "%\\nG71/' "$moore")
refused "a '%' in the Moore header" "$m.yaml" "$m.machine.yaml:13:3:" "words after the program's end (% on line 2)" "header comes from the dialect settings"
m=$(machine_variant header_m30 's/^  header: "G71/  header: "M30\\nG71/' "$moore")
refused "an M30 in the Moore header" "$m.yaml" "$m.machine.yaml:13:3:" "words after the program's end (M30 on line 2)"
m=$(machine_variant percent_word 's/^  header: "G71/  header: "G71 %/' "$moore")
refused "a '%' among a header's words" "$m.yaml" "$m.machine.yaml:13:3:" "'%' inside a block"
# Block times at 3 decimals: the scheduled whole microseconds rounded to milliseconds took
# the demo's C to 2.9 times its acceleration limit, read back from the program.
m=$(machine_variant time_ms 's/^  child_blocks: .*/&\n  time_decimals: 3/' "$moore")
refused "Moore block times at 3 decimals" "$m.yaml" "$m.machine.yaml:19:18:" "'time_decimals' is 3, outside [6, 9]"
# Two codes of one RS-274 modal group in a block contradict each other: a controller refuses it.
m=$(machine_variant motion_twice 's/^  header: "G71 G01 G18/  header: "G71 G01 G00 G18/' "$moore")
refused "G01 and G00 in the Moore header's block" "$m.yaml" "$m.machine.yaml:13:3:" "two G codes of RS-274's motion group in one block"
# Modes the program's words were not written for: incremental distances, a preset of X.
m=$(machine_variant incremental 's/^  header: "G71 G01 G18 G40 G63 G90/  header: "G71 G01 G18 G40 G63 G91/' "$moore")
refused "G91 in the Moore header" "$m.yaml" "$m.machine.yaml:13:3:" "an axis word under G91 (incremental distances, line 2)"
m=$(machine_variant preset_x 's/G92 C0.0"/G92 X5.0 C0.0"/' "$moore")
refused "a preset of X in the Moore header" "$m.yaml" "$m.machine.yaml:13:11:" "dialect setting 'header' gives X or Z in the work frame ('G92 X5.0 C0.0')"
# A footer that moves in the work frame: after the retract, into the part's centre.
m=$(machine_variant footer_plunge 's/^  footer: "G53 Z-180./  footer: "G00 X0 Z-0.5\\nG53 Z-180./' "$moore")
refused "a footer's move into the part" "$m.yaml" "$m.machine.yaml:14:11:" "dialect setting 'footer' gives X or Z in the work frame ('G00 X0 Z-0.5')"
# An approach feed beyond Z's velocity (25 mm/s = 1500 mm/min): at the dialect settings.
m=$(machine_variant fast_approach 's/^  approach_feed: 200/  approach_feed: 9000/' "$moore")
refused "an approach feed beyond Z's velocity" "$m.yaml" "$m.machine.yaml:13:3:" "F9000.000 a minute (G94) moves Z at 150 mm/s, beyond its max_velocity 25"
# A turn of C beside Y under a feed per minute takes Y's time, which no line settles.
m=$(machine_variant turn_beside 's/G92 C0.0"/G92 C0.0\\nF100\\nY0 C10"/' "$moore")
refused "a turn of C beside Y in the Moore header" "$m.yaml" "$m.machine.yaml:13:3:" "C10 turns from C0.0 together with a linear axis in a feed per minute (G94)"
# A comment left open swallows the rest of its block: G01 G18 … would never be read.
m=$(machine_variant open_comment 's/^  header: "G71/  header: "G71 (note/' "$moore")
refused "an unclosed comment in the Moore header" "$m.yaml" "$m.machine.yaml:13:3:" "a comment '(' without ')' on its line"

# A cut the machine cannot make (exit 1, nothing written) is reported at the limit it
# crosses in the machine file, with the place on the path.
failed() {  # description, job, expected prefix, words...
  local what="$1" job="$2" where="$3"
  shift 3
  cases=$((cases + 1))
  for command in check run; do
    rm -rf "$tmp/out"
    mkdir -p "$tmp/out"
    local args=("$job")
    [[ "$command" == run ]] && args+=(-o "$tmp/out")
    "$freeturn" "$command" "${args[@]}" > "$tmp/err" 2>&1
    local code=$?
    [[ "$code" == 1 ]] || { echo "FAIL: $what ($command): exit $code, expected 1"; cat "$tmp/err"; fail=1; continue; }
    grep -qF -- "FAIL: $where" "$tmp/err" || { echo "FAIL: $what ($command): no 'FAIL: $where' in:"; cat "$tmp/err"; fail=1; }
    for word in "$@"; do
      grep -qF -- "$word" "$tmp/err" || { echo "FAIL: $what ($command): '$word' not in:"; cat "$tmp/err"; fail=1; }
    done
    [[ -z "$(ls -A "$tmp/out")" ]] || { echo "FAIL: $what ($command): left $(ls -A "$tmp/out")"; fail=1; }
  done
}
m=$(machine_variant x_travel 's/min: -100, max: 100, decimals: 6/min: -100, max: 1.5, decimals: 6/')
failed "X travel shorter than the aperture" "$m.yaml" "$m.machine.yaml:5:40:" "machine axis X max 1.5" "r = 2" "outside its travel"
# The part itself above the Z travel: the path's failure, in check as in run (check had
# probed the approach from the part's top first, and refused it as bad input, exit 2).
m=$(machine_variant z_below 's/min: -50, max: 50, decimals: 6/min: -50, max: 0.01, decimals: 6/')
failed "Z travel below the part" "$m.yaml" "$m.machine.yaml:6:39:" "machine axis Z max 0.01" "outside its travel"
cp "$src/postprocessors/iso/machines/iso-lathe-xzcb.yaml" "$tmp/xzcb.yaml"
sed -i 's/min_deg: -60, max_deg: 60/min_deg: -0.5, max_deg: 60/' "$tmp/xzcb.yaml"
sed "s|^machine: .*|machine: $tmp/xzcb.yaml|; s/^strategy:/strategy:\n  b_axis: follow/" "$base" > "$tmp/b_limit.yaml"
failed "B beyond its limits" "$tmp/b_limit.yaml" "$tmp/xzcb.yaml:10:19:" "machine.b_axis.min_deg" "B = -2.29" "tool-rotation limits [-0.5"

# The size bound on job and machine files is FREETURN_MAX_YAML_MB.
cases=$((cases + 1))
{ cat "$base"; printf '# %02000d\n' 0; } > "$tmp/padded.yaml"  # 2.4 kB
FREETURN_MAX_YAML_MB=0.003 "$freeturn" check "$tmp/padded.yaml" > /dev/null 2> "$tmp/err" ||
  { echo "FAIL: FREETURN_MAX_YAML_MB=0.003 refuses a 2.4 kB job"; cat "$tmp/err"; fail=1; }
FREETURN_MAX_YAML_MB=0.001 "$freeturn" check "$tmp/padded.yaml" > /dev/null 2> "$tmp/err"
code=$?
[[ $code == 2 ]] && grep -qF "$tmp/padded.yaml: the file has" "$tmp/err" && grep -qF "1048-byte bound" "$tmp/err" ||
  { echo "FAIL: FREETURN_MAX_YAML_MB=0.001: exit $code"; cat "$tmp/err"; fail=1; }
FREETURN_MAX_YAML_MB=lots "$freeturn" check "$base" > /dev/null 2> "$tmp/err"
[[ $? == 2 ]] && grep -qF "FREETURN_MAX_YAML_MB: must be a size in MiB" "$tmp/err" ||
  { echo "FAIL: FREETURN_MAX_YAML_MB=lots"; cat "$tmp/err"; fail=1; }

# An inline NURBS: a knot or weight fault at the knot or weight itself.
sampled() {  # description, job, expected prefix, word
  cases=$((cases + 1))
  rm -rf "$tmp/out"
  "$freeturn" sample "$2" -o "$tmp/out" > /dev/null 2> "$tmp/err"
  local code=$?
  [[ "$code" == 2 ]] || { echo "FAIL: $1: exit $code, expected 2"; fail=1; }
  [[ "$(head -c ${#3} "$tmp/err")" == "$3" ]] || { echo "FAIL: $1: stderr does not start with '$3':"; cat "$tmp/err"; fail=1; }
  grep -qF -- "$4" "$tmp/err" || { echo "FAIL: $1: '$4' not in:"; cat "$tmp/err"; fail=1; }
  [[ -z "$(ls -A "$tmp/out" 2> /dev/null)" ]] || { echo "FAIL: $1: left $(ls -A "$tmp/out")"; fail=1; }
}
# A sample grid past the job's file limit: refused before evaluating (its rows cannot fit)
# or as it grows; nothing is left (a 20001-point grid had written about 30 GB).
{ cat "$src/configs/jobs/oap_segment.yaml"; echo "limits: {max_file_mb: 1}"; } > "$tmp/samples.yaml"
limits_line=$(grep -n '^limits:' "$tmp/samples.yaml" | cut -d: -f1)
for grid in 2001 201; do
  cases=$((cases + 1))
  rm -rf "$tmp/out"
  (cd "$src/configs/jobs" && "$freeturn" sample "$tmp/samples.yaml" -o "$tmp/out" --grid $grid) > /dev/null 2> "$tmp/err"
  code=$?
  [[ $code == 2 ]] || { echo "FAIL: samples of a $grid grid: exit $code"; fail=1; }
  grep -qF "$tmp/samples.yaml:$limits_line:23: limits.max_file_mb: the samples of a $grid × $grid grid" "$tmp/err" ||
    { echo "FAIL: samples of a $grid grid:"; cat "$tmp/err"; fail=1; }
  [[ -z "$(ls -A "$tmp/out" 2> /dev/null)" ]] || { echo "FAIL: samples of a $grid grid left $(ls -A "$tmp/out")"; fail=1; }
done
grep -qF "grow past limits.max_file_mb = 1 MB" "$tmp/err" || { echo "FAIL: the grid that grows past:"; cat "$tmp/err"; fail=1; }

cat > "$tmp/nurbs.yaml" <<'YAML'
name: n
aperture:
  outer_radius: 0.4
surface:
  type: nurbs
  degree_u: 1
  degree_v: 1
  knots_u: [0, 0, 1, 1]
  knots_v: [0, 0, 0.5, 1, 1]
  points: [[-1, -1, 0], [-1, 0, 0], [-1, 1, 0], [1, -1, 0], [1, 0, 0], [1, 1, 0]]
  weights: [1, 1, 1, 1, -2, 1]
YAML
sampled "a negative weight" "$tmp/nurbs.yaml" "$tmp/nurbs.yaml:11:25:" "surface.weights[4]"
sed 's/knots_v: \[0, 0, 0.5, 1, 1\]/knots_v: [0, 0, 0.7, 0.5, 1]/; s/-2/1/' "$tmp/nurbs.yaml" > "$tmp/knots.yaml"
sampled "decreasing knots" "$tmp/knots.yaml" "$tmp/knots.yaml:9:24:" "surface.knots_v[3]"
# A least-squares height grid smoothed 1e16 had lost its x-y to rounding (the aperture then
# lay beyond a 7 µm surface, reported at the data); the weight is refused at its own key.
cat > "$tmp/grid.yaml" <<'YAML'
name: g
aperture:
  outer_radius: 1.0
surface:
  type: height_grid
  x: [-1.5, -0.75, 0, 0.75, 1.5]
  y: [-1.5, -0.75, 0, 0.75, 1.5]
  z: [[0, 0, 0, 0, 0], [0, 1, 1, 1, 0], [0, 1, 2, 1, 0], [0, 1, 1, 1, 0], [0, 0, 0, 0, 0]]
  fit: least_squares
  control_points: [4, 4]
  smoothing: 1e16
YAML
sampled "a smoothing weight that swamps the grid" "$tmp/grid.yaml" "$tmp/grid.yaml:11:14:" "surface.smoothing is 1e+16, more than 1e8 times"

# The same weight on a measured error's B-spline is refused at its key in the job, not at
# the measurement file.
sed -e "s|fit: {zernike: 21}|fit: {zernike: 21, bspline: {control_points: 12, smoothing: 1e30}}|" \
    -e "s|\.\./data/|$src/configs/data/|" \
    "$src/configs/jobs/compound_eye_compensated.yaml" > "$tmp/heavy.yaml"
refused "a B-spline smoothing that swamps the measurement" "$tmp/heavy.yaml" "$tmp/heavy.yaml:24:63:" \
  "compensation.fit.bspline.smoothing is 1e+30, more than 1e8 times"

# A measurement wrong as a whole has no line of its own: reported at the job's `measured`
# key, naming the file. Three points cannot register and fit 21 Zernike terms; a
# directory or a device is no data file (/dev/zero had been read as one endless line).
sed -e "s|\.\./data/compound_eye_measured.xyz|$tmp/three.xyz|" -e 's/format: zygo_xyz .*/format: xyz/' \
    -e '/^  origin:/d' "$src/configs/jobs/compound_eye_compensated.yaml" > "$tmp/three.yaml"
printf '0 0 0\n1 0 0\n0 1 0\n' > "$tmp/three.xyz"
refused "a measurement of three points" "$tmp/three.yaml" "$tmp/three.yaml:19:13:" \
  "compensation.measured '$tmp/three.xyz': 3 valid points fall inside the aperture"
sed "s|$tmp/three.xyz|/dev/zero|" "$tmp/three.yaml" > "$tmp/zero.yaml"
refused "a device as the measurement" "$tmp/zero.yaml" "$tmp/zero.yaml:19:13:" "'/dev/zero': is not a regular file"
mkdir -p "$tmp/folder.xyz"
sed "s|$tmp/three.xyz|$tmp/folder.xyz|" "$tmp/three.yaml" > "$tmp/folder.yaml"
refused "a directory as the measurement" "$tmp/folder.yaml" "$tmp/folder.yaml:19:13:" "is not a regular file"
# A line of the measurement that is no point is refused at the measurement file's line and
# column, the first field that is not a number: "0 1e-3 z0" has it at column 8.
printf '0 0 0\n1 0 0\n0 1e-3 z0\n' > "$tmp/field.xyz"
sed "s|$tmp/three.xyz|$tmp/field.xyz|" "$tmp/three.yaml" > "$tmp/field.yaml"
refused "a measurement point that is not a number" "$tmp/field.yaml" "$tmp/field.xyz:3:8:" \
  "'z0' is not a finite number"
# The same for a point cloud named as the design, after the job's `file` key that names
# it: the field "1e-3x" of its third line, from column 5.
printf 'x y z\n0 0 0\n1 0 1e-3x\n0 1 0\n1 1 0\n' > "$tmp/cloud.xyz"
sed "s|^  type: sphere\$|  type: point_cloud\n  file: $tmp/cloud.xyz\n  control_points: [4, 4]|; s|^  radius: 50.0\$||" \
  "$base" > "$tmp/cloud.yaml"
refused "a point cloud's field that is not a number" "$tmp/cloud.yaml" "$tmp/cloud.yaml:6:9:" \
  "$tmp/cloud.xyz:3:5: expected three numbers x y z (mm); '1e-3x' is not a finite number"

# Refusals found while planning or posting, far from the file, name the job's key that
# leads to them. A compound eye whose lenslets (radius 1 mm, 0.9 mm wide) tilt the normal
# 27.5° from its base's (sin α = 0.45/1 on the rim, less the base's tilt) is past the 10°
# limit of quasi-revolution: reported at the limit's key.
sed -e 's/lens_radius: -5.0 .*/lens_radius: -1.0/' "$src/configs/jobs/compound_eye.yaml" > "$tmp/steep_eye.yaml"
refused "lenslets past quasi-revolution" "$tmp/steep_eye.yaml" "$tmp/steep_eye.yaml:22:58:" \
  "strategy.base_surface.max_normal_deviation_deg:" "not of quasi-revolution for its base: α reaches 27.4"
# A chord-rule spiral on the Precitech, whose dialect writes no time a block: over a sphere
# decentred 3 mm the steps vary (equal angles, or steps all at max_angle_deg, would not),
# which the post refuses at the job's machine key, in `check` as in `run` (check posts the
# program into no file; it had passed).
sed -e "s|^machine: .*|machine: precitech-nanoform-250|" -e 's/max_angle_deg: 5/max_angle_deg: 30/' \
    -e 's/^  radius: 50.0/  radius: 50.0\n  decenter: {x: 3}/' "$base" > "$tmp/precitech_chord.yaml"
refused "varying block times on a dialect without them" "$tmp/precitech_chord.yaml" "$tmp/precitech_chord.yaml:19:10:" \
  "machine: post-processor 'precitech'" "block times vary" "use equal-angle points"
# A job that can only be sampled has no line to blame: its first.
printf 'name: plate\naperture: {outer_radius: 2}\nsurface: {type: sphere, radius: 50}\n' > "$tmp/sample_only.yaml"
refused "a job with nothing to run" "$tmp/sample_only.yaml" "$tmp/sample_only.yaml:1:1:" "no tool, strategy, cutting and machine sections"

# SIGTERM and SIGINT mid-run remove the temporaries, as an error does. (Job control on:
# without it a background job ignores SIGINT, and freeturn leaves an ignored signal so.)
set -m
# A run that writes from its first second and goes on for many: 14 M chord points (equal
# angles and arcs first plan an estimate of their stand-off, writing nothing meanwhile).
slow=$(variant slow 's/chord: {tolerance: 0.001, max_angle_deg: 5}/chord: {tolerance: 0.001, max_angle_deg: 0.001}/')
for signal in TERM INT; do
  rm -rf "$tmp/out"
  "$freeturn" run "$slow" -o "$tmp/out" --quiet 2> /dev/null &
  pid=$!
  for _ in $(seq 100); do [[ -n "$(ls -A "$tmp/out" 2> /dev/null)" ]] && break; sleep 0.05; done
  [[ -n "$(ls -A "$tmp/out" 2> /dev/null)" ]] || { echo "FAIL: SIG$signal: the run wrote nothing to interrupt"; fail=1; }
  kill -s "$signal" "$pid"
  wait "$pid"
  code=$?
  [[ "$code" -gt 128 ]] || { echo "FAIL: SIG$signal: exit $code, expected death by the signal"; fail=1; }
  [[ -z "$(ls -A "$tmp/out")" ]] || { echo "FAIL: SIG$signal left $(ls -A "$tmp/out")"; fail=1; }
done
set +m

echo "$cases cases"
exit $fail
