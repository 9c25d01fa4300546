#!/usr/bin/env bash
# report.html renders in headless Chromium (Debian's chromium) without errors: the page
# loads, the DOM holds the figures table, the plots and the residual heat map, the browser logs no console
# or page error, and the screenshot is not blank. Skipped (exit 77) without chromium;
# CI installs it (.ci/run).
# usage: report_html_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
browser=$(command -v chromium || command -v chromium-browser || true)
[[ -n "$browser" ]] || { echo "chromium not installed (apt-get install chromium): skipped"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$freeturn" run "$src/configs/jobs/oap_segment.yaml" -o "$tmp/out" --quiet --simulate || { echo "FAIL: the job did not run"; exit 1; }
page="file://$tmp/out/report.html"
flags=(--headless --no-sandbox --disable-gpu --no-first-run --user-data-dir="$tmp/profile"
       --enable-logging=stderr --v=0)
"$browser" "${flags[@]}" --dump-dom "$page" > "$tmp/dom.html" 2> "$tmp/dom.log"
"$browser" "${flags[@]}" --window-size=1280,1600 --screenshot="$tmp/shot.png" "$page" > /dev/null 2> "$tmp/shot.log"
fail=0
# The path from above, the error along the radius, points per revolution, X and Z velocity,
# and the simulated residual's heat map (an SVG holding a BMP image and its colour bar).
[[ $(grep -o '<svg' "$tmp/dom.html" | wc -l) == 6 ]] || { echo "FAIL: the DOM does not hold the six SVG plots"; fail=1; }
grep -q '<image[^>]*href="data:image/bmp;base64,Qk' "$tmp/dom.html" || { echo "FAIL: no heat map image"; fail=1; }
grep -q 'worst place' "$tmp/dom.html" || { echo "FAIL: no table of the worst places"; fail=1; }
grep -q '<table>' "$tmp/dom.html" || { echo "FAIL: the DOM has no figures table"; fail=1; }
grep -q 'oap_segment on iso-lathe-xzc' "$tmp/dom.html" || { echo "FAIL: the title is missing"; fail=1; }
if grep -E 'CONSOLE|Uncaught|ERROR:.*(html|svg|render)' "$tmp/dom.log" "$tmp/shot.log"; then
  echo "FAIL: the browser logged errors"; fail=1
fi
size=$(stat -c %s "$tmp/shot.png" 2> /dev/null || echo 0)
[[ $size -gt 20000 ]] || { echo "FAIL: the screenshot is missing or blank ($size bytes)"; fail=1; }
[[ $fail == 0 ]] && echo "1 passed, 0 failed"
exit $fail
