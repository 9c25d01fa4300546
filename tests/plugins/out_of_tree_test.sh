#!/usr/bin/env bash
# The template post builds out of tree against the plugin headers alone (as installed),
# and freeturn finds and loads it through FREETURN_PLUGIN_PATH.
# usage: out_of_tree_test.sh <freeturn> <source dir>
set -u
freeturn=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/include/freeturn"
cp "$src/plugins/include/freeturn/post_plugin.h" "$src/plugins/include/freeturn/post_format.hpp" \
   "$src/plugins/include/freeturn/post_settings.hpp" "$tmp/include/freeturn/"
g++ -std=c++20 -O2 -fPIC -shared -fvisibility=hidden -Wall -Wextra -Werror -I"$tmp/include" \
    "$src/plugins/template/template_post.cpp" -o "$tmp/libfreeturn_post_template.so" || {
  echo "FAIL: the template does not build out of tree"; exit 1; }
FREETURN_PLUGIN_PATH="$tmp" "$freeturn" plugins > "$tmp/out" || { echo "FAIL: freeturn plugins"; exit 1; }
grep -qF "template  ($tmp/libfreeturn_post_template.so)  ok" "$tmp/out" || {
  echo "FAIL: the template plugin is not listed as loadable:"; cat "$tmp/out"; exit 1; }
echo "1 passed, 0 failed"
