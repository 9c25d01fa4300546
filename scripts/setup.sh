#!/usr/bin/env bash
# Installs the Debian 12 packages freeturn needs (when missing), then configures and
# builds one build flavour. Idempotent: with everything in place it only runs an
# incremental build.
#
#   scripts/setup.sh [release|asan|fuzz]
#                                     install what is missing, configure, build
#                                     (release: optimised, with a profile of its own
#                                      runs unless FREETURN_PGO=off, for the demo and bench/;
#                                      asan: AddressSanitizer + UBSan, for the tests;
#                                      fuzz: clang with libFuzzer, the fuzz/ harnesses)
#   scripts/setup.sh --check          list the missing packages, one per line;
#                                     exit 0 if none is missing, 1 otherwise
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# Everything the build, the tests and the benchmarks use. Keep in step with
# third_party.cmake, which names the same packages when a find fails.
packages=(
  cmake g++ make pkg-config
  libeigen3-dev libopenmesh-dev libyaml-cpp-dev doctest-dev
  libbenchmark-dev libcli11-dev nlohmann-json3-dev
  # The tests' report.json schema check and the locale test's de_DE definition.
  python3-jsonschema locales
  # The tests' independent NC reader (tests/jobs/nc_dynamics.py).
  python3
  # The Python module (python/) and its tests.
  python3-dev pybind11-dev python3-numpy python3-pytest
)
# Extra packages a caller (CI) wants too, e.g. FREETURN_EXTRA_PACKAGES="linuxcnc-uspace".
read -r -a extra <<< "${FREETURN_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")

missing_packages() {
  local p
  for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}\n' "$p" 2>/dev/null | grep -q "install ok installed"; then
      echo "$p"
    fi
  done
}

if [[ "${1:-}" == "--check" ]]; then
  missing="$(missing_packages)"
  if [[ -z "$missing" ]]; then
    echo "all ${#packages[@]} packages are installed"
    exit 0
  fi
  echo "$missing"
  exit 1
fi

flavour="${1:-release}"
case "$flavour" in
  release) cmake_args=(-DCMAKE_BUILD_TYPE=Release -DFREETURN_BUILD_BENCH=ON -DFREETURN_BUILD_TESTS=OFF) ;;
  asan) cmake_args=(-DCMAKE_BUILD_TYPE=Debug -DFREETURN_SANITIZE=ON) ;;
  fuzz)
    # libFuzzer and the sanitizer runtimes come with clang's compiler-rt.
    packages+=(clang libclang-rt-14-dev)
    cmake_args=(-DCMAKE_BUILD_TYPE=Debug -DFREETURN_FUZZ=ON -DFREETURN_BUILD_TESTS=OFF
                -DCMAKE_CXX_COMPILER=clang++)
    ;;
  *) echo "setup.sh: unknown build flavour '$flavour' (release, asan or fuzz)" >&2; exit 2 ;;
esac

mapfile -t missing < <(missing_packages)
if ((${#missing[@]})); then
  if [[ "$(id -u)" -ne 0 ]]; then
    echo "setup.sh: missing Debian packages; run as root, or run:" >&2
    echo "  sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
    exit 2
  fi
  echo "setup.sh: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build="$root/build/$flavour"
# release: the library built from a profile of its own runs (kernel/CMakeLists.txt,
# FREETURN_PGO). Once per build folder an instrumented build plans a finishing pass
# (configs/training), then the library is built again from what it recorded. The profile
# changes no value, only the code's layout (docs/path.md, "Build"). FREETURN_PGO=off skips
# it; removing build/release/pgo trains again. Sources edited since the training still
# build (kernel/CMakeLists.txt: -fprofile-correction), with their old profile where it fits.
if [[ "$flavour" == release && "${FREETURN_PGO:-on}" != off ]]; then
  profile="$build/pgo"
  if [[ ! -f "$profile/trained" ]]; then
    echo "setup.sh: training the release build's profile (configs/training)"
    cmake -S "$root" -B "$build" "${cmake_args[@]}" -DFREETURN_PGO=generate \
      -DFREETURN_PGO_DIR="$profile" >/dev/null
    cmake --build "$build" --parallel "$(nproc)" --target freeturn_cli freeturn_post_moore
    rm -rf "$profile"
    mkdir -p "$profile"
    scratch="$(mktemp -d)"
    trap 'rm -rf "$scratch"' EXIT
    "$build/bin/freeturn" run "$root/configs/training/compound_eye_fine_pitch.yaml" \
      -o "$scratch" --quiet --threads 1 >/dev/null
    touch "$profile/trained"
  fi
  cmake_args+=(-DFREETURN_PGO=use -DFREETURN_PGO_DIR="$profile")
else
  cmake_args+=(-DFREETURN_PGO=)
fi
# Configuring again is quick with a cache, and repairs a build folder left half-configured.
cmake -S "$root" -B "$build" "${cmake_args[@]}" >/dev/null
if [[ "$flavour" == fuzz ]]; then
  # The harnesses only: the CLI, posts and plugins are the other flavours' business.
  cmake --build "$build" --parallel "$(nproc)" --target freeturn_fuzzers
else
  cmake --build "$build" --parallel "$(nproc)"
fi
