#!/usr/bin/env bash
# The README's demo command: set up (packages, optimised build), then run the demo job,
# a compound eye cut with a space spiral on a Moore Nanotech 250UPL.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh" release
out="${1:-$root/out/demo}"
"$root/build/release/bin/freeturn" run "$root/configs/jobs/compound_eye.yaml" -o "$out"
