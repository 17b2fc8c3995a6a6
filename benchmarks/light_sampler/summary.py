#!/usr/bin/env python3
"""Summary of benchmarks/light_sampler/run.sh: per scene, the median over
rounds of (a) the equal-time gain, efficiency 1/(MSE x time) of the light BVH
over power at each one's last point, (b) the MSE ratio at equal samples, and
(c) samples per second, the light BVH over power.

Usage: summary.py OUT COMMIT"""
import csv
import os
import re
import statistics
import sys

out, commit = sys.argv[1], sys.argv[2]
device = "?"
rows = []
for name in sorted(os.listdir(out)):
    d = os.path.join(out, name)
    if not os.path.isdir(d) or name == "references":
        continue
    gains, mse_ratios, speed = [], [], []
    spp = None
    for rnd in sorted(os.listdir(d)):
        f = os.path.join(d, rnd, "convergence.csv")
        md = os.path.join(d, rnd, "convergence.md")
        if not os.path.isfile(f):
            continue
        with open(md) as m:
            hit = re.search(r", on \[\d+\] ([^(]+) \(", m.read())
            if hit:
                device = hit.group(1).strip()
        last = {}
        for r in csv.DictReader(open(f)):
            c = r["config"]
            if c not in last or int(r["spp"]) > int(last[c]["spp"]):
                last[c] = r
        p, b = last.get("lights-power"), last.get("lights-bvh")
        if not p or not b:
            continue
        ep = 1 / (float(p["mse"]) * float(p["seconds"]))
        eb = 1 / (float(b["mse"]) * float(b["seconds"]))
        gains.append(eb / ep)
        speed.append((int(b["spp"]) / float(b["seconds"])) / (int(p["spp"]) / float(p["seconds"])))
        if p["spp"] == b["spp"]:
            mse_ratios.append(float(p["mse"]) / float(b["mse"]))
        spp = (p["spp"], b["spp"])
    if gains:
        rows.append((name, len(gains), spp, gains, mse_ratios, speed))

fmt = lambda v: "%.3g" % v
print("# Light samplers at equal time: the light BVH against power\n")
print("`benchmarks/light_sampler/run.sh` at commit %s, on %s (PoCL). Each round is one"
      " `clpath bench convergence --configs lights-power,lights-bvh` (64x48; cornell-classic 64x64),"
      " against a 32768-spp clpath reference rendered with the light BVH (`references/`)."
      " **Equal-time gain**: 1/(MSE x time) of the light BVH over power at each one's last point"
      " (how many times less squared error the light BVH has in the same time); the median of the"
      " rounds, every round in brackets.\n" % (commit, device))
print("| scene | rounds | last spp (power, bvh) | equal-time gain | MSE ratio at equal spp (power / bvh) | samples/s, bvh / power |")
print("|---|--:|---|--:|--:|--:|")
for name, n, spp, g, m, s in rows:
    print("| %s | %d | %s, %s | **%s** (%s) | %s (%s) | %s (%s) |" % (
        name, n, spp[0], spp[1], fmt(statistics.median(g)), ", ".join(fmt(x) for x in g),
        fmt(statistics.median(m)) if m else "-", ", ".join(fmt(x) for x in m),
        fmt(statistics.median(s)), ", ".join(fmt(x) for x in s)))
