#!/usr/bin/env bash
# The module layering of docs/conventions.md ("Layout"), read from the code:
#   - a kernel module includes only its own headers and those of the modules listed before
#     it in FREETURN_MODULES (kernel/CMakeLists.txt, the one place the order is written);
#   - the command line (apps/) includes the library's facade (freeturn/freeturn.hpp) and
#     the files layer (freeturn/io/) only;
#   - the plugin SDK (plugins/include) and the posts (postprocessors/) include no kernel
#     header: a plugin is standard C++ and the ABI alone.
# Usage: module_layers_test.sh SOURCE_DIR
set -u
src=$1
cd "$src" || exit 1
order=$(sed -n 's/^set(FREETURN_MODULES \(.*\))$/\1/p' kernel/CMakeLists.txt)
[ -n "$order" ] || { echo "FREETURN_MODULES not found in kernel/CMakeLists.txt"; exit 1; }
sdk=$(ls plugins/include/freeturn | tr '\n' ' ')
fail=0
rank() {  # the module's position in the order, or -1
  local i=0
  for m in $order; do [ "$m" = "$1" ] && { echo $i; return; }; i=$((i + 1)); done
  echo -1
}
for m in $order; do
  mine=$(rank "$m")
  [ -d "kernel/src/$m" ] || { echo "module $m has no kernel/src/$m"; fail=1; }
  while IFS=: read -r file line text; do
    dep=$(sed -n 's|.*#include "freeturn/\([a-z_]*\)/.*|\1|p' <<<"$text")
    [ -n "$dep" ] || continue
    r=$(rank "$dep")
    if [ "$r" -lt 0 ] || [ "$r" -gt "$mine" ]; then
      echo "$file:$line: module '$m' includes freeturn/$dep/ (above it, or no module)"
      fail=1
    fi
  done < <(grep -rn '#include "freeturn/' "kernel/src/$m" "kernel/include/freeturn/$m" 2>/dev/null)
done
# A folder under kernel/src that is not in the order is not built: a mistake.
for d in kernel/src/*/; do
  d=$(basename "$d")
  [ "$(rank "$d")" -ge 0 ] || { echo "kernel/src/$d is not in FREETURN_MODULES"; fail=1; }
done
while IFS=: read -r file line text; do
  case "$text" in
    *'"freeturn/freeturn.hpp"'* | *'"freeturn/io/'*) ;;
    *) echo "$file:$line: the command line includes more than the facade and io: $text"; fail=1 ;;
  esac
done < <(grep -rn '#include "freeturn/' apps)
while IFS=: read -r file line text; do
  header=$(sed -n 's|.*#include [<"]freeturn/\([^">]*\)[">].*|\1|p' <<<"$text")
  case " $sdk " in
    *" $header "*) ;;
    *) echo "$file:$line: a plugin-side file includes a kernel header: $text"; fail=1 ;;
  esac
done < <(grep -rnE '#include [<"]freeturn/' plugins/include plugins/template postprocessors)
[ $fail -eq 0 ] && echo "layers: $(wc -w <<<"$order") modules in order, apps and plugins apart"
exit $fail
