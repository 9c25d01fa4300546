#!/usr/bin/env bash
# setup.sh --check must list exactly the packages dpkg does not report as installed.
# A fake dpkg-query on PATH stands in for dpkg, so the test controls what is "installed".
set -euo pipefail
setup="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

cat > "$tmp/dpkg-query" <<'FAKE'
#!/usr/bin/env bash
# Called as: dpkg-query -W -f=FORMAT PACKAGE
pkg="${@: -1}"
for p in $FAKE_INSTALLED; do
  if [[ "$p" == "$pkg" ]]; then echo "install ok installed"; exit 0; fi
done
echo "dpkg-query: no packages found matching $pkg" >&2
exit 1
FAKE
chmod +x "$tmp/dpkg-query"

all="cmake g++ make pkg-config libeigen3-dev libopenmesh-dev libyaml-cpp-dev doctest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev python3-jsonschema locales python3 python3-dev pybind11-dev python3-numpy python3-pytest"
fail=0
check() {  # $1: installed list, $2: expected output, $3: expected exit code
  local out code
  set +e
  out="$(PATH="$tmp:$PATH" FAKE_INSTALLED="$1" FREETURN_EXTRA_PACKAGES="${EXTRA:-}" bash "$setup" --check)"
  code=$?
  set -e
  if [[ "$out" != "$2" || "$code" != "$3" ]]; then
    echo "FAIL: installed='$1' extra='${EXTRA:-}'"
    echo "  expected (exit $3): $(echo "$2" | tr '\n' ' ')"
    echo "  got      (exit $code): $(echo "$out" | tr '\n' ' ')"
    fail=1
  fi
}

check "$all" "all 18 packages are installed" 0
check "cmake g++ make pkg-config libeigen3-dev libyaml-cpp-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev python3-jsonschema locales python3 python3-dev pybind11-dev python3-numpy python3-pytest" \
      $'libopenmesh-dev\ndoctest-dev' 1
check "" "$(echo "$all" | tr ' ' '\n')" 1
EXTRA="linuxcnc-uspace" check "$all" "linuxcnc-uspace" 1

if ((fail)); then exit 1; fi
echo "setup.sh --check: 4 cases as expected"
