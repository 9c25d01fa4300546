#!/usr/bin/env bash
# Every file a run writes (NC, CL CSV, residual CSV and PLY, OBJ, VTK, report JSON and
# HTML) has the same bytes under a German locale (decimal comma) as under "C": no number
# goes through the C library's locale-dependent formatting. The de_DE.UTF-8 definition is
# compiled into a temporary folder with localedef (Debian's `locales` package holds its
# source); skipped (exit 77) without it.
# usage: locale_test.sh <run_in_locale> <source dir>
set -u
runner=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/locales"
if ! localedef -i de_DE -f UTF-8 "$tmp/locales/de_DE.UTF-8" > /dev/null 2>&1; then
  echo "no de_DE definition to compile (apt-get install locales): skipped"; exit 77
fi
export LOCPATH="$tmp/locales"
# glibc's setlocale keeps a composite locale name it never frees; LeakSanitizer would fail
# the sanitizer build's run for that alone.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
fail=0
# The off-axis parabola with its mesh and CL outputs; the Alvarez plate for the Moore post,
# B and child files.
for job in oap_segment alvarez_4axis; do
  (cd "$src/configs/jobs" && "$runner" C "$job.yaml" "$tmp/c/$job") > "$tmp/c.txt" || { echo "FAIL: $job did not run in C"; fail=1; continue; }
  (cd "$src/configs/jobs" && "$runner" de_DE.UTF-8 "$job.yaml" "$tmp/de/$job") > "$tmp/de.txt"
  rc=$?
  [[ $rc == 77 ]] && { echo "de_DE.UTF-8 did not load: skipped"; exit 77; }
  [[ $rc == 0 ]] || { echo "FAIL: $job did not run under de_DE.UTF-8"; fail=1; continue; }
  # The locale took hold: printf itself writes a decimal comma there.
  [[ $(cat "$tmp/c.txt") == "1.50" && $(cat "$tmp/de.txt") == "1,50" ]] || { echo "FAIL: the locale did not change printf"; fail=1; }
  count=$(ls "$tmp/c/$job" | wc -l)
  [[ $count -ge 6 ]] || { echo "FAIL: $job wrote only $count files"; fail=1; }
  if diff -r "$tmp/c/$job" "$tmp/de/$job" > "$tmp/diff.txt"; then
    echo "$job: $count files, the same bytes under de_DE.UTF-8 and C"
  else
    echo "FAIL: $job's files differ under de_DE.UTF-8:"; head -5 "$tmp/diff.txt"; fail=1
  fi
done
[[ $fail == 0 ]] && echo "1 passed, 0 failed"
exit $fail
