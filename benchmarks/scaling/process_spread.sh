#!/usr/bin/env bash
# How far one ray batch's speed moves between fresh processes, against how far
# it moves between the launches of one process: says whether a machine can
# give the stable scaling table (coefficient of variation under 5 % between
# runs) by longer batches, or whether the spread is the machine's, between
# processes, which no batch size averages out.
#   benchmarks/scaling/process_spread.sh DEVICE_DIR [DEVICE_SPEC] [BUILD_DIR]
# runs `clpath bench rays SCENE --launches LAUNCHES --no-embree` PROCS times, one
# process after another, and writes benchmarks/results/DEVICE_DIR/scaling/
# process-spread.{md,csv} (each process's mean and best launch per batch, the
# coefficient of variation of each between processes).
# Environment: PROCS (6), LAUNCHES (15), SCENE (scaling:1000000), NOTE (a line on the machine's state).
set -euo pipefail
DIR=${1:?usage: process_spread.sh DEVICE_DIR [DEVICE_SPEC] [BUILD_DIR]}
SPEC=${2:-}
B=${3:-build}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
CLPATH="$B/clpath"
[ -x "$CLPATH" ] || { echo "process_spread.sh: $CLPATH is not built" >&2; exit 2; }
PROCS=${PROCS:-6}
LAUNCHES=${LAUNCHES:-15}
SCENE=${SCENE:-scaling:1000000}
OUT="$ROOT/benchmarks/results/$DIR/scaling"
mkdir -p "$OUT"
DEV=()
[ -n "$SPEC" ] && DEV=(--device "$SPEC")
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
START=$(date -u +%FT%TZ)
LOAD_BEFORE=$(cut -d' ' -f1-3 /proc/loadavg)
echo "process,start,load1,batch,rays,launches,mean_ms,best_ms,mrays_per_s" > "$WORK/spread.csv"
for p in $(seq 1 "$PROCS"); do
  t=$(date -u +%T)
  l=$(cut -d' ' -f1 /proc/loadavg)
  echo "== process $p at $t (load $l)"
  "$CLPATH" bench rays "$SCENE" --launches "$LAUNCHES" --check 4096 --no-embree "${DEV[@]}" --csv "$WORK/p.csv" \
    > "$WORK/p.txt" 2> "$WORK/p.err" || { cat "$WORK/p.err" >&2; exit 1; }
  python3 - "$WORK/p.csv" "$p" "$t" "$l" >> "$WORK/spread.csv" <<'PY'
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    print(f"{sys.argv[2]},{sys.argv[3]},{sys.argv[4]},{r['batch']},{r['rays']},{r['launches']},{r['mean_ms']},{r['best_ms']},{r['mrays_per_s']}")
PY
  device=$(grep -m1 'device "' "$WORK/p.txt" | sed 's/.*device "\(.*\)"/\1/' || true)
done
cp "$WORK/spread.csv" "$OUT/process-spread.csv"
python3 - "$OUT" "$START" "$(date -u +%FT%TZ)" "$(git -C "$ROOT" rev-parse --short HEAD)" "$device" "$SCENE" "$LAUNCHES" \
  "$LOAD_BEFORE" "$(cut -d' ' -f1-3 /proc/loadavg)" "${NOTE:-}" <<'PY'
import csv, statistics as st, sys
out, start, end, commit, device, scene, launches, before, after, note = sys.argv[1:]
rows = list(csv.DictReader(open(f"{out}/process-spread.csv")))
cv = lambda xs: st.pstdev(xs) / st.mean(xs) * 100
L = ["# How far a ray batch moves between processes", ""]
L.append(f"- Device: `{device}`. Date: {start} to {end}. Commit: {commit}.")
L.append(f"- Load average before / after: {before} / {after}." + (f" {note}" if note else ""))
L.append(f"- Command, once per process, one process after another: `clpath bench rays {scene} --launches {launches} "
         "--check 4096 --no-embree` (`benchmarks/scaling/process_spread.sh`; every process's rows in "
         "`process-spread.csv`). Each batch: one warm-up launch, then the timed ones.")
L.append("- Between processes: the coefficient of variation (standard deviation over mean) of the processes' "
         "mean launch time, and of their best launch. Within a process: its mean over its best launch.")
L.append("")
L.append("| batch | rays | processes | mean ms per process | CV of the means | best ms per process | CV of the bests | mean / best within a process |")
L.append("|---|---:|---:|---|---:|---|---:|---|")
for batch in dict.fromkeys(r["batch"] for r in rows):
    rs = [r for r in rows if r["batch"] == batch]
    means = [float(r["mean_ms"]) for r in rs]
    bests = [float(r["best_ms"]) for r in rs]
    L.append(f"| {batch} | {rs[0]['rays']} | {len(rs)} | {' '.join(f'{m:.1f}' for m in means)} | {cv(means):.1f} % "
             f"| {' '.join(f'{b:.1f}' for b in bests)} | {cv(bests):.1f} % "
             f"| {min(m / b for m, b in zip(means, bests)):.3f}-{max(m / b for m, b in zip(means, bests)):.3f} |")
L.append("")
worst = max(cv([float(r["best_ms"]) for r in rows if r["batch"] == b]) for b in {r["batch"] for r in rows})
if worst > 5:
    L.append(f"Even each process's best launch moves by up to {worst:.1f} % between processes, so longer or more "
             "launches per batch cannot bring runs in fresh processes within 5 % of each other on this machine: "
             "what moves, moves from one process to the next (the machine's state, or where each process's "
             "memory lands), not from launch to launch.")
else:
    L.append(f"Each process's best launch moves by at most {worst:.1f} % between processes: runs in fresh "
             "processes can agree within 5 % here.")
open(f"{out}/process-spread.md", "w").write("\n".join(L) + "\n")
print("\n".join(L))
PY
echo "process_spread.sh: wrote $OUT/process-spread.{md,csv}"
