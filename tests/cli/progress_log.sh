#!/usr/bin/env bash
# A render whose output goes to a file, not a terminal, writes a progress line
# at least every interval, even while no tenth of the work is crossed: the
# watchdog thread's lines. CLPATH_PROGRESS_INTERVAL_MS shortens the interval
# from 10 s (covered by tests/cli/progress_test.cpp) so the test takes seconds.
#   progress_log.sh CLPATH OUT_DIR
#
# The checks read the times printed in the lines themselves and the render's
# own render_s, so a slow machine only makes the render longer. The watchdog
# sleeps until the next line is due (no polling period), so on time the gaps
# are the interval exactly, give or take the 0.1 s the stamps are rounded to.
# Scheduling delays on a loaded machine make a line late, never early; the
# checks allow every wake-up to be late by up to a whole further interval
# (1 s), which a thread that sleeps almost all the time does not meet.
set -euo pipefail
clpath=$1
out=$2
mkdir -p "$out"
log=$out/progress.log
rm -f "$log" "$out/progress.pfm"
interval_ms=1000
run_s=5

# spp too large for a tenth to pass in seconds: after the first line (0 %),
# every line comes from the watchdog.
CLPATH_PROGRESS_INTERVAL_MS=$interval_ms "$clpath" render --spp 4294967295 --width 16 --height 16 --seed 3 \
    -o "$out/progress.pfm" >"$log" 2>&1 &
pid=$!
for _ in $(seq 1200); do
    grep -q '^progress:' "$log" && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.1
done
grep -q '^progress:' "$log" || { cat "$log"; echo "no progress line before the render ended"; kill $pid; exit 1; }
sleep $run_s
kill -INT $pid
rc=0
wait $pid || rc=$?
cat "$log"
[ $rc -eq 130 ] || { echo "a render interrupted by SIGINT exited $rc, not 130"; exit 1; }

/usr/bin/env python3 - "$log" "$interval_ms" <<'EOF'
import re, sys
text = open(sys.argv[1]).read()
interval = int(sys.argv[2]) / 1000
stamps = [float(x) for x in re.findall(r'^progress: +\d+%  \d+ spp  ([0-9.]+) s elapsed', text, re.M)]
end = float(re.search(r'render_s=([0-9.]+)', text).group(1))
rounding = 0.1  # two stamps, each rounded to 0.05 s
gaps = [b - a for a, b in zip(stamps, stamps[1:])]
print(f"{len(stamps)} lines over {end:.3f} s; gaps {', '.join(f'{g:.1f}' for g in gaps)}")
# Never more often than the interval: that is the rule the watchdog follows.
early = [g for g in gaps if g < interval - rounding]
# Never further apart than the interval plus the wake-up allowance above.
late = [g for g in gaps + [end - stamps[-1]] if g > 2 * interval + rounding]
# On time there are floor(end / interval) + 1 lines; half of that is the bound.
least = int(end / interval) // 2 + 1
ok = True
if early:
    print(f"lines closer than the interval {interval} s: {early}"); ok = False
if late:
    print(f"gaps longer than twice the interval: {late}"); ok = False
if len(stamps) < least:
    print(f"{len(stamps)} lines, fewer than {least} over {end:.3f} s"); ok = False
if end < 3 * interval:
    print(f"the render lasted {end:.3f} s, too short to check an interval of {interval} s"); ok = False
sys.exit(0 if ok else 1)
EOF
