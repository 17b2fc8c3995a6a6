#!/usr/bin/env python3
"""README.md for benchmarks/bvh_build/run.sh: clpath's builder beside tinybvh's,
per scene and round, from runs.csv and tinybvh-runs.csv.

usage: summarise.py OUT_DIR META_FILE
META_FILE holds key=value lines (date_start, date_end, commit, tinybvh_commit,
cpu, cores, threads, rounds, note). Rows of the two programs are paired by
round and triangle count. Each ratio is tinybvh's time over clpath's (above 1:
clpath builds faster), the median of the rounds' ratios."""
import csv
import statistics
import sys
from pathlib import Path


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    out, meta_file = Path(sys.argv[1]), Path(sys.argv[2])
    meta = dict(line.rstrip("\n").split("=", 1) for line in open(meta_file) if "=" in line)
    clp = [r for r in rows(out / "runs.csv") if r["binary"] == "clpath"]
    tb = rows(out / "tinybvh-runs.csv")
    builders = list(dict.fromkeys(r["builder"] for r in tb))
    loads = [float(r["load1"]) for r in clp + tb]
    cores = int(meta.get("cores", "2"))
    # A note says what else ran; one that starts "shared" marks the machine shared whatever its load.
    note = meta.get("note", "")
    shared = max(loads) > 1.25 * cores or note.lower().startswith("shared")

    lines = []
    add = lines.append
    add("# BVH build time: clpath against tinybvh's builders")
    add("")
    add(f"- Device: the host CPU (the builder runs on the host, not the OpenCL device): {meta['cpu']}, {cores} cores; "
        f"clpath with {meta['threads']} build threads; tinybvh's builders as tinybvh runs them: BuildAVX and Build "
        "start two threads per split in their top 5 levels for meshes of 50,000 triangles or more "
        "(MT_BUILD_THRESHOLD), which both scenes here are; BuildHQ likewise.")
    add(f"- Date: {meta['date_start']} to {meta['date_end']}. clpath commit: {meta['commit']}. tinybvh commit: "
        f"{meta['tinybvh_commit']} (1.6.7), compiled by `benchmarks/bvh_build/tinybvh/build.sh` with `-O3 -march=native` "
        "as tinybvh's own CMake file compiles it, so BuildDefault is BuildAVX on this CPU.")
    if shared:
        add(f"- **The machine was shared** with other work: load average (1 min) {min(loads):.1f} to {max(loads):.1f} "
            f"on {cores} cores. {note.rstrip('.') + '. ' if note else ''}The two programs ran back to back in every round, the order "
            "alternating, so each ratio compares runs that met about the same load; absolute times are above an "
            "idle machine's. Retake on an idle machine with the command below.")
    else:
        add(f"- Load average (1 min) {min(loads):.1f} to {max(loads):.1f} on {cores} cores (idle but for the builders)."
            + (f" {note}" if note else ""))
    add(f"- Command: `TINYBVH_DIR=<tinybvh checkout> ROUNDS={meta['rounds']} benchmarks/bvh_build/run.sh <this folder's "
        "name>`; every entry is the median of 3 builds in one process (`log.txt`, `runs.csv`, `tinybvh-runs.csv`).")
    add("- SAH cost: the same measure for both (each interior node's area plus each leaf's area times its triangles, "
        "over the root's area; host/bvh/binned_builder.cpp and the harness's `facts`).")
    add("")
    head = "| scene | triangles | clpath ms | clpath SAH | " + " | ".join(
        f"{b} ms | {b} SAH | clpath speed / {b}" for b in builders) + " |"
    add(head)
    add("|---|---:|" + "---:|" * (2 + 3 * len(builders)))
    for tris in dict.fromkeys(r["triangles"] for r in clp):
        c = {r["round"]: r for r in clp if r["triangles"] == tris}
        cells = [c[next(iter(c))]["scene"], f"{int(tris):,}",
                 f"{statistics.median(float(r['median_ms']) for r in c.values()):.1f}",
                 f"{float(c[next(iter(c))]['sah_cost']):.2f}"]
        for b in builders:
            t = {r["round"]: r for r in tb if r["triangles"] == tris and r["builder"] == b}
            ratios = [float(t[k]["median_ms"]) / float(c[k]["median_ms"]) for k in c if k in t]
            if not ratios:
                cells += ["–", "–", "–"]
                continue
            spread = f" ({min(ratios):.2f}–{max(ratios):.2f})" if len(ratios) > 1 else ""
            cells += [f"{statistics.median(float(r['median_ms']) for r in t.values()):.1f}",
                      f"{float(next(iter(t.values()))['sah_cost']):.2f}",
                      f"**{statistics.median(ratios):.2f}**{spread}"]
        add("| " + " | ".join(cells) + " |")
    add("")
    add("Times are medians over the rounds; \"clpath speed / X\" is X's time over clpath's in the same round (above 1: "
        "clpath is faster), the median of the rounds with their range.")
    add("")
    (out / "README.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
