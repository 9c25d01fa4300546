#!/usr/bin/env bash
# The README's demo command: set up (packages, optimised build), then run the demo job.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh" release
out="${1:-$root/out/demo}"
"$root/build/release/bin/freeturn" sample "$root/configs/jobs/demo_asphere.yaml" -o "$out"
