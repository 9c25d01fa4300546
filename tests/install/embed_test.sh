#!/usr/bin/env bash
# freeturn installed and found: `cmake --install` into a temporary prefix, then
# examples/embed configured out of tree with find_package(freeturn) and built against it,
# and the pkg-config file read. The embedding program runs a job through
# freeturn::run_job (finding the plugins and machines beside the installed library), and
# its NC programs equal the command line's byte for byte.
# usage: embed_test.sh <build dir> <source dir> <freeturn> <extra compiler flags>
set -u
build=$1 src=$2 freeturn=$3 flags=${4:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
unset FREETURN_PLUGIN_PATH FREETURN_MACHINE_PATH
fail=0
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log" 2>&1 ||
  { echo "FAIL: cmake --install"; tail "$tmp/install.log"; exit 1; }
for f in lib/libfreeturn.so lib/cmake/freeturn/freeturnConfig.cmake \
         lib/cmake/freeturn/freeturnConfigVersion.cmake lib/pkgconfig/freeturn.pc \
         include/freeturn/freeturn.hpp include/freeturn/post_plugin.h lib/freeturn/libfreeturn_post_iso.so; do
  [[ -e "$tmp/prefix/$f" ]] || { echo "FAIL: the install has no $f"; fail=1; }
done
"$tmp/prefix/bin/freeturn" plugins | grep -q "iso-lathe-xzc" ||
  { echo "FAIL: the installed freeturn does not find its plugins and machines"; fail=1; }
soname=$(objdump -p "$tmp/prefix/lib/libfreeturn.so" | awk '/SONAME/ {print $2}')
[[ "$soname" == libfreeturn.so.* ]] || { echo "FAIL: libfreeturn.so has SONAME '$soname'"; fail=1; }
PKG_CONFIG_PATH="$tmp/prefix/lib/pkgconfig" pkg-config --cflags --libs freeturn | grep -q -- "-lfreeturn" ||
  { echo "FAIL: pkg-config does not give -lfreeturn"; fail=1; }
if ! cmake -S "$src/examples/embed" -B "$tmp/embed" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
     -DCMAKE_CXX_FLAGS="$flags" > "$tmp/configure.log" 2>&1 ||
   ! cmake --build "$tmp/embed" > "$tmp/build.log" 2>&1; then
  echo "FAIL: examples/embed does not configure and build against the install"
  tail -20 "$tmp/configure.log" "$tmp/build.log"; exit 1
fi
# The Python module from the prefix alone: it finds libfreeturn and, through it, the
# installed plugins and machines (check_job loads the post).
if [[ "${FREETURN_TEST_PYTHON:-OFF}" == ON ]]; then
  module=$(ls "$tmp/prefix"/lib/python3/dist-packages/freeturn*.so 2>/dev/null | head -1)
  if [[ -z "$module" ]]; then
    echo "FAIL: the install has no Python module under lib/python3/dist-packages"; fail=1
  else
    out=$(cd "$tmp" && env ${FREETURN_TEST_PRELOAD:+LD_PRELOAD=$FREETURN_TEST_PRELOAD} ASAN_OPTIONS=detect_leaks=0 \
          PYTHONPATH="$tmp/prefix/lib/python3/dist-packages" PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 -c '
import sys, freeturn
print(freeturn.__file__)
print(freeturn.check_job(sys.argv[1])["verdict"])' "$src/configs/jobs/oap_segment.yaml" 2>&1)
    if [[ "$(head -1 <<<"$out")" != "$tmp/prefix/lib/python3/dist-packages/"* ]] ||
       [[ "$(tail -1 <<<"$out")" != PASS ]]; then
      echo "FAIL: the installed Python module: $out"; fail=1
    else
      echo "python: the installed module checks oap_segment: $(tail -1 <<<"$out")"
    fi
  fi
fi
for job in oap_segment sinusoidal_ring; do
  "$tmp/embed/run_job" "$src/configs/jobs/$job.yaml" "$tmp/embedded/$job" > "$tmp/embed.txt" ||
    { echo "FAIL: run_job $job"; cat "$tmp/embed.txt"; fail=1; continue; }
  (cd "$src/configs/jobs" && "$freeturn" run "$job.yaml" -o "$tmp/cli/$job" --quiet) ||
    { echo "FAIL: freeturn run $job"; fail=1; continue; }
  count=0
  for nc in "$tmp/cli/$job"/*.nc; do
    count=$((count + 1))
    cmp -s "$nc" "$tmp/embedded/$job/$(basename "$nc")" ||
      { echo "FAIL: $job: $(basename "$nc") differs from the command line's"; fail=1; }
  done
  echo "$job: $count NC files equal the command line's; $(head -1 "$tmp/embed.txt")"
done
exit $fail
