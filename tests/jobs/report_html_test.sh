#!/usr/bin/env bash
# The report renders in headless Chromium (Debian's chromium) without errors and holds
# what docs/report.md promises, by id: the verdict, the summary and the job's parameters,
# the warnings, the part with its path, the predicted form error map, the charts along the
# radius (chord error, finish, axis velocities and accelerations, points per revolution)
# and the worst places. The page is self-contained: no script, nothing fetched (its only
# URL is the SVG namespace). The browser logs no console or page error and the screenshot
# is not blank. Skipped (exit 77) without chromium; CI installs it (.ci/run).
# usage: report_html_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
browser=$(command -v chromium || command -v chromium-browser || true)
[[ -n "$browser" ]] || { echo "chromium not installed (apt-get install chromium): skipped"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$freeturn" run "$src/configs/jobs/oap_segment.yaml" -o "$tmp/out" --quiet --simulate || { echo "FAIL: the job did not run"; exit 1; }
html="$tmp/out/oap_segment.report.html"
page="file://$html"
flags=(--headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking
       --disable-component-update --disable-sync --user-data-dir="$tmp/profile"
       --enable-logging=stderr --v=0)
"$browser" "${flags[@]}" --dump-dom "$page" > "$tmp/dom.html" 2> "$tmp/dom.log"
"$browser" "${flags[@]}" --window-size=1280,1600 --screenshot="$tmp/shot.png" "$page" > /dev/null 2> "$tmp/shot.log"
fail=0
for id in verdict summary parameters warnings fig-part fig-form-error fig-chord fig-finish \
          fig-velocity-X fig-velocity-Z fig-velocity-C fig-acceleration-X fig-acceleration-Z \
          fig-points-per-revolution passes simulation worst job-yaml; do
  grep -q "id=\"$id\"" "$tmp/dom.html" || { echo "FAIL: the rendered page has no #$id"; fail=1; }
done
# The maps are images inside their SVGs; the charts have axes with tick labels and titles.
[[ $(grep -o '<image[^>]*href="data:image/bmp;base64,Qk' "$tmp/dom.html" | wc -l) == 2 ]] || { echo "FAIL: not two map images"; fail=1; }
grep -q '>r (mm)</text>' "$tmp/dom.html" || { echo "FAIL: no axis title r (mm)"; fail=1; }
grep -q 'tolerance 100.0 nm' "$tmp/dom.html" || { echo "FAIL: the chord chart has no tolerance line"; fail=1; }
grep -q 'PASS' "$tmp/dom.html" || { echo "FAIL: no verdict"; fail=1; }
if grep -qi '<script' "$html"; then echo "FAIL: the page has a script"; fail=1; fi
if grep -o 'https\?://[^"<> ]*' "$html" | grep -v '^http://www.w3.org/2000/svg$' | grep -q .; then
  echo "FAIL: the page refers to something outside itself"; fail=1
fi
if grep -E 'CONSOLE|Uncaught|ERROR:.*(html|svg|render)' "$tmp/dom.log" "$tmp/shot.log"; then
  echo "FAIL: the browser logged errors"; fail=1
fi
size=$(stat -c %s "$tmp/shot.png" 2> /dev/null || echo 0)
[[ $size -gt 20000 ]] || { echo "FAIL: the screenshot is missing or blank ($size bytes)"; fail=1; }
[[ $fail == 0 ]] && echo "1 passed, 0 failed"
exit $fail
