#!/usr/bin/env bash
# Crash-safe outputs: `freeturn run` killed with SIGKILL at random moments, over and over,
# never leaves a partial file under a final name and never damages what was there
# before. Every output file must afterwards be byte-identical either to what was there
# before the run (a marker written first) or to the complete output of an undisturbed run;
# a main program may instead be set aside whole as <name>.replaced-<pid> while the run's
# files are renamed (io/output_set.hpp). And a main program an operator could load is
# never beside files it was not written with: an old one only while every file is old, a
# new one only once every file is new.
# usage: kill_test.sh <freeturn> <source dir> <job> <kills>
set -u
freeturn=$1 src=$2 job=$3 kills=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
start=$(date +%s%N)
"$freeturn" run "$src/configs/jobs/$job.yaml" -o "$tmp/ref" --quiet || { echo "FAIL: the job did not run"; exit 1; }
run_ms=$(( ($(date +%s%N) - start) / 1000000 ))
mapfile -t outputs < <(cd "$tmp/ref" && ls)
mkdir "$tmp/out"
for f in "${outputs[@]}"; do printf 'OLD %s\n' "$f" > "$tmp/out/$f"; cp "$tmp/out/$f" "$tmp/old.$f"; done
fail=0 kept_old=0 complete=0 mixed=0 set_aside=0 leftovers=0
for ((i = 1; i <= kills; i++)); do
  "$freeturn" run "$src/configs/jobs/$job.yaml" -o "$tmp/out" --quiet > /dev/null 2>&1 &
  pid=$!
  # Anywhere from the start to a little past the undisturbed run's end.
  sleep "$(awk -v ms="$run_ms" -v r="$RANDOM" 'BEGIN { printf "%.3f", ms * 1.2 * r / 32767 / 1000 }')"
  kill -KILL "$pid" 2> /dev/null
  wait "$pid" 2> /dev/null
  old=0 new=0 mains_old=0 mains_new=0
  for f in "${outputs[@]}"; do
    is_main=0
    [[ $f == *.nc && $f != *_[0-9][0-9][0-9].nc ]] && is_main=1
    if [[ ! -e "$tmp/out/$f" ]]; then
      aside=("$tmp/out/$f".replaced-*)
      if [[ ${#aside[@]} == 1 && -e ${aside[0]} ]] && cmp -s "${aside[0]}" "$tmp/old.$f"; then
        set_aside=$((set_aside + 1)); old=$((old + 1))
      else echo "FAIL: kill $i removed $f without setting it aside whole"; fail=1; break 2
      fi
    elif cmp -s "$tmp/out/$f" "$tmp/old.$f"; then old=$((old + 1)); mains_old=$((mains_old + is_main))
    elif cmp -s "$tmp/out/$f" "$tmp/ref/$f"; then new=$((new + 1)); mains_new=$((mains_new + is_main))
    else echo "FAIL: kill $i left $f neither as it was nor complete"; fail=1; break 2
    fi
  done
  if ((mains_old > 0 && new > 0)); then
    echo "FAIL: kill $i left an earlier main program beside $new new files"; fail=1; break
  fi
  if ((mains_new > 0 && old > 0)); then
    echo "FAIL: kill $i left a new main program beside $old earlier files"; fail=1; break
  fi
  ((new == 0)) && kept_old=$((kept_old + 1))
  ((old == 0)) && complete=$((complete + 1))
  ((old > 0 && new > 0)) && mixed=$((mixed + 1))
  # Back to the old state, so every kill lands on a file that was there before.
  rm -f "$tmp/out"/*.replaced-*
  for f in "${outputs[@]}"; do cp "$tmp/old.$f" "$tmp/out/$f"; done
done
# A killed run cannot remove its temporaries (they never carry a final name); the next
# run of the same outputs does.
"$freeturn" run "$src/configs/jobs/$job.yaml" -o "$tmp/out" --quiet || { echo "FAIL: the last run failed"; fail=1; }
for f in "${outputs[@]}"; do cmp -s "$tmp/out/$f" "$tmp/ref/$f" || { echo "FAIL: the last run left $f different"; fail=1; }; done
leftovers=$(find "$tmp/out" -name '*.tmp-*' -o -name '*.replaced-*' | wc -l)
[[ $leftovers == 0 ]] || { echo "FAIL: $leftovers temporary files left after a complete run"; fail=1; }
echo "$kills kills over a ${run_ms} ms run: $kept_old left every file as it was, $complete found the run complete, $mixed between with no main program in place (set aside: $set_aside files); no temporary or set-aside file left after the next complete run"
[[ $fail == 0 ]] && echo "1 passed, 0 failed"
exit $fail
