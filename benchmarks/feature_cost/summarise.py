#!/usr/bin/env python3
"""Medians of run.sh's rounds as Markdown tables (Debian's python3, standard library).

Usage: summarise.py render render-runs.csv | summarise.py load load-runs.csv"""
import csv
import statistics
import sys
from collections import defaultdict


def medians(rows, key, value):
    groups = defaultdict(list)
    for r in rows:
        if r[value]:
            groups[key(r)].append(float(r[value]))
    return {k: (statistics.median(v), min(v), max(v), len(v)) for k, v in groups.items()}


def fmt(m, digits=3):
    return f"{m[0]:.{digits}f} ({m[1]:.{digits}f}-{m[2]:.{digits}f}, n={m[3]})" if m else "-"


def ratio(a, b):
    return f"{a[0] / b[0]:.3f}" if a and b and b[0] > 0 else "-"


def paired(rows, a, b):
    """Median and range over rounds of a's rate / b's rate in the same round (the two
    ran minutes apart at most, so they saw more similar load than rates from different rounds)."""
    by_round = defaultdict(dict)
    for r in rows:
        if r["msamples_per_s"]:
            by_round[r["round"]][(r["binary"], r["scene"], r["options"])] = float(r["msamples_per_s"])
    ratios = [v[a] / v[b] for v in by_round.values() if a in v and b in v and v[b] > 0]
    if not ratios:
        return "-"
    return f"{statistics.median(ratios):.2f} ({min(ratios):.2f}-{max(ratios):.2f})"


def render(rows):
    med = medians(rows, lambda r: (r["binary"], r["scene"], r["options"]), "msamples_per_s")
    print("Msamples/s, median of the rounds (min-max, rounds); higher is faster.\n")
    print("### Scenes without textures: this build against the builds before the material split and before glTF\n")
    print("Ratios: of the medians, and in brackets the median (min-max) of the same round's ratios.\n")
    print("| scene | kernel | this | before split (793641d) | before glTF (a0af516) | this / before split | this / before glTF |")
    print("|---|---|---|---|---|---|---|")
    for scene in ("cornell-classic", "bunny"):
        for opt in ("specialised", "--all-features"):
            t, s, g = (med.get((b, scene, opt)) for b in ("this", "pre_split", "pre_gltf"))
            ps = paired(rows, ("this", scene, opt), ("pre_split", scene, opt))
            pg = paired(rows, ("this", scene, opt), ("pre_gltf", scene, opt))
            print(f"| {scene} | {opt} | {fmt(t)} | {fmt(s)} | {fmt(g)} | {ratio(t, s)} [{ps}] | {ratio(t, g)} [{pg}] |")
    print("\n### Textured scenes against the same scenes with one grey diffuse material\n")
    print("| scene | build | textured | plain | textured / plain | this / before split, textured |")
    print("|---|---|---|---|---|---|")
    for textured, plain in (("textured", "textured-plain"), ("suzanne-textured", "suzanne-plain")):
        for b, name in (("this", "this"), ("pre_split", "before split (793641d)")):
            t, p = med.get((b, textured, "specialised")), med.get((b, plain, "specialised"))
            same = paired(rows, (b, textured, "specialised"), (b, plain, "specialised"))
            cross = paired(rows, ("this", textured, "specialised"), ("pre_split", textured, "specialised"))
            if t or p:
                print(f"| {textured} | {name} | {fmt(t)} | {fmt(p)} | {ratio(t, p)} [{same}] | {cross if b == 'this' else ''} |")


def load(rows):
    med = medians(rows, lambda r: (r["binary"], r["file"]), "load_s")
    print("Load seconds (clpath render's \"loaded ... in X s\": reading, parsing, building the scene), "
          "median of the rounds (min-max, rounds); lower is faster.\n")
    print("| file | before | this | before / this |")
    print("|---|---|---|---|")
    for f in sorted({k[1] for k in med}):
        b, t = med.get(("before", f)), med.get(("this", f))
        print(f"| {f} | {fmt(b)} | {fmt(t)} | {ratio(b, t)} |")


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("render", "load"):
        sys.exit(__doc__)
    with open(sys.argv[2]) as f:
        rows = list(csv.DictReader(f))
    (render if sys.argv[1] == "render" else load)(rows)


if __name__ == "__main__":
    main()
