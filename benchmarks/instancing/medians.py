#!/usr/bin/env python3
"""The medians over the rounds of benchmarks/instancing/run.sh: one table
per scene, Mrays/s of every tracer and batch, and clpath's two-level walk
over each (a ratio of medians). Usage: medians.py RESULT_DIR COMMIT."""
import csv
import datetime
import glob
import os
import statistics
import sys

out, commit = sys.argv[1], sys.argv[2]
rows = {}
device = ""
for path in sorted(glob.glob(os.path.join(out, "bunnies-*-round*.csv"))):
    with open(path) as f:
        for r in csv.DictReader(f):
            device = r["device"]
            key = (int(r["instances"]), int(r["placed_triangles"]), r["batch"], r["tracer"])
            rows.setdefault(key, []).append(float(r["mrays_per_s"]))
            rows.setdefault(key + ("differing",), []).append(int(r["differing"]))
print(f"# Instancing: clpath bench instances, {datetime.date.today()}, commit {commit}\n")
print(f"Device: {device}. 240x160 pixels x 16 samples, 3 timed launches (Embree: passes) per batch; "
      f"Mrays/s are the median of {max(len(v) for v in rows.values())} rounds. "
      "'clpath/this' is clpath's two-level walk over the tracer named (medians). "
      "'differ': rays whose answer is not the two-level walk's (largest over the rounds).\n")
scenes = sorted({(k[0], k[1]) for k in rows if len(k) == 4})
tracers = ["clpath instanced", "clpath flattened", "Embree instanced default", "Embree instanced robust",
           "Embree flattened default", "Embree flattened robust"]
for inst, placed in scenes:
    print(f"## bunnies:{inst} ({placed:,} triangles placed)\n")
    txt = os.path.join(out, f"bunnies-{inst}-round1.txt")
    if os.path.exists(txt):
        for line in open(txt):
            if line.startswith(("two-level:", "flattened:")):
                print(f"- {line.strip()}")
        print()
    print("| tracer | " + " | ".join(f"{b} Mrays/s | clpath/this | differ" for b in ("primary", "shadow", "diffuse")) + " |")
    print("|---|" + "---|---|---|" * 3)
    for t in tracers:
        cells = []
        for b in ("primary", "shadow", "diffuse"):
            v = rows.get((inst, placed, b, t))
            if not v:
                cells += ["—", "—", "—"]
                continue
            m = statistics.median(v)
            own = statistics.median(rows[(inst, placed, b, "clpath instanced")])
            cells += [f"{m:.2f}", f"{own / m:.2f}" if t != "clpath instanced" else "1", str(max(rows[(inst, placed, b, t, "differing")]))]
        if any(c != "—" for c in cells):
            print(f"| {t} | " + " | ".join(cells) + " |")
    print()
