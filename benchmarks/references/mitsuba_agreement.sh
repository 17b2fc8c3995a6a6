#!/usr/bin/env bash
# The full-size agreement of clpath with the Mitsuba 3 references: the test
# program of tests/references/ at twice the CI size (the references' own for
# most) with 4x
# the samples per run (CLPATH_MITSUBA_FULL=1), its verdicts and figures (per
# pixel, image mean ratio +- standard error) written to
# benchmarks/references/mitsuba-agreement.txt with the device and commit.
#
# Usage: benchmarks/references/mitsuba_agreement.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
B=${1:-$root/build}
test_bin=$B/tests/mitsuba_agreement_test
[ -x "$test_bin" ] || { echo "mitsuba_agreement.sh: no $test_bin: build it first" >&2; exit 1; }
out=$root/benchmarks/references/mitsuba-agreement.txt
{
  echo "date: $(date -u +%FT%TZ)  commit: $(git -C "$root" rev-parse --short HEAD)  load: $(cut -d' ' -f1-3 /proc/loadavg)"
  "$B/clpath" devices | sed -n 2p | sed 's/^ *//'
  (cd "$root" && CLPATH_MITSUBA_FULL=1 CLPATH_CACHE_DIR="$B/kernel-cache" "$test_bin" --gtest_filter='Reference/*' 2>&1) |
    grep -E '^\[ mitsuba \]|^\[  (PASSED|FAILED)|tests? ran'
} | tee "$out"
