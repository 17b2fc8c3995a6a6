#!/usr/bin/env bash
# A render whose output goes to a file, not a terminal, writes a progress line
# at least every interval, even while no tenth of the work is crossed: the
# watchdog thread's lines. CLPATH_PROGRESS_INTERVAL_MS shortens the interval
# from 10 s (covered by tests/cli/progress_test.cpp) so the test takes seconds.
#   progress_log.sh CLPATH OUT_DIR
#
# The checks read the times printed in the lines themselves, so a slow machine
# only makes the render longer. The watchdog sleeps until the next line is due
# (no polling period), so on time the gaps are the interval exactly, give or
# take the 0.1 s the stamps are rounded to. Scheduling delays on a loaded
# machine make a line late, never early; the checks allow every wake-up to be
# late by up to a whole further interval (1 s), which a thread that sleeps
# almost all the time does not meet. The render is interrupted once the log
# holds enough lines to check, not after a fixed time: how long the devices
# take to get ready (kernel compiles, a busy machine) does not matter.
set -euo pipefail
clpath=$1
out=$2
mkdir -p "$out"
log=$out/progress.log
rm -f "$log" "$out/progress.pfm"
interval_ms=1000
lines=6  # the first (0 %), then five from the watchdog: over 4 intervals to check

# spp too large for a tenth to pass in seconds: after the first line (0 %),
# every line comes from the watchdog.
CLPATH_PROGRESS_INTERVAL_MS=$interval_ms "$clpath" render --spp 4294967295 --width 16 --height 16 --seed 3 \
    -o "$out/progress.pfm" >"$log" 2>&1 &
pid=$!
progress_lines() {
    local n
    n=$(grep -c '^progress:' "$log" 2>/dev/null) || true
    echo "${n:-0}"
}
# Without the watchdog only the first line comes: give up after minutes.
for ((i = 0; i < 1800; ++i)); do
    [ "$(progress_lines)" -ge $lines ] && break
    kill -0 $pid 2>/dev/null || { cat "$log"; echo "the render ended before $lines progress lines"; exit 1; }
    sleep 0.1
done
[ "$(progress_lines)" -ge $lines ] || { kill $pid; cat "$log"; echo "fewer than $lines progress lines in 3 minutes"; exit 1; }
kill -INT $pid
rc=0
wait $pid || rc=$?
cat "$log"
[ $rc -eq 130 ] || { echo "a render interrupted by SIGINT exited $rc, not 130"; exit 1; }

/usr/bin/env python3 - "$log" "$interval_ms" "$lines" <<'EOF'
import re, sys
text = open(sys.argv[1]).read()
interval = int(sys.argv[2]) // 100  # in tenths of a second, the stamps' unit
least = int(sys.argv[3])
# Whole tenths, so that a gap is compared exactly (no binary rounding of 0.1).
stamps = [int(a) * 10 + int(b) for a, b in
          re.findall(r'^progress: +\d+%  \d+ spp  (\d+)\.(\d) s elapsed', text, re.M)]
rounding = 1  # two stamps, each rounded to 0.05 s: one tenth
gaps = [b - a for a, b in zip(stamps, stamps[1:])]
print(f"{len(stamps)} lines; gaps {', '.join(f'{g / 10:.1f}' for g in gaps)} s")
ok = True
# Never more often than the interval: that is the rule the watchdog follows.
early = [g / 10 for g in gaps if g < interval - rounding]
if early:
    print(f"lines closer than the interval {interval / 10} s: {early}"); ok = False
# Never further apart than the interval plus the wake-up allowance above.
late = [g / 10 for g in gaps if g > 2 * interval + rounding]
if late:
    print(f"gaps longer than twice the interval: {late}"); ok = False
if len(stamps) < least:
    print(f"{len(stamps)} lines, fewer than the {least} waited for"); ok = False
sys.exit(0 if ok else 1)
EOF
