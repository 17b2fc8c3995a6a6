#!/usr/bin/env python3
"""Medians of the side-by-side rounds (benchmarks/rays/side_by_side.sh):
summary.csv and README.md from clpath-runs.csv and tinybvh-runs.csv.

usage: summarise.py OUT_DIR META_FILE
META_FILE holds key=value lines (date, commit, tinybvh_commit, device, ...).
Ratios are the median over rounds of each round's ratio (clpath and the other
tracer ran back to back in each round, so they met about the same load)."""
import csv
import datetime
import math
import statistics
import sys
from collections import defaultdict
from pathlib import Path

LAYOUTS = [("BVH_GPU", "ailalaine"), ("BVH4_GPU", "gpu4way"), ("BVH8_CWBVH", "cwbvh")]
BATCHES = ["primary", "shadow", "diffuse"]


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def median(xs):
    return statistics.median(xs) if xs else float("nan")


def fmt(x, digits=2):
    return "–" if x != x else f"{x:.{digits}f}"


def main():
    out, meta_file = Path(sys.argv[1]), Path(sys.argv[2])
    meta = dict(line.rstrip("\n").split("=", 1) for line in open(meta_file) if "=" in line)
    clp = rows(out / "clpath-runs.csv")
    tb = rows(out / "tinybvh-runs.csv")

    # (scene, batch, round) -> row
    c_at = {(r["scene"], r["batch"], r["round"]): r for r in clp}
    # Each layout's trees from tinybvh's BuildHQ and Build (the harness's --build hq,fast): per round
    # and batch the faster of the two counts, as a user would pick it.
    t_at = {}
    for r in tb:
        key = (r["scene"], r["layout"], r["batch"], r["round"])
        if key not in t_at or float(r["mrays_per_s"]) > float(t_at[key]["mrays_per_s"]):
            t_at[key] = r
    scenes = list(dict.fromkeys(r["scene"] for r in clp))
    layouts = [(s, k) for s, k in LAYOUTS if any(r["layout"] == s for r in tb)]
    loads = [float(r["load1"]) for r in clp + tb]

    summary = []
    for scene in scenes:
        for batch in BATCHES:
            rounds = sorted({r["round"] for r in clp if r["scene"] == scene and r["batch"] == batch}, key=int)
            if not rounds:
                continue
            c = [c_at[(scene, batch, k)] for k in rounds]
            s = {
                "scene": scene,
                "triangles": c[0]["triangles"],
                "batch": batch,
                "rays": c[0]["rays"],
                "rounds": len(rounds),
                "clpath_mrays_per_s": median([float(r["mrays_per_s"]) for r in c]),
                "clpath_mismatched": max(int(r["mismatched"]) for r in c),
            }
            # Embree in its default mode (as its users run it) first, then robust (watertight, like clpath).
            for mode in ("default", "robust"):
                s[f"embree_{mode}_mrays_per_s"] = median(
                    [float(r[f"embree_{mode}_mrays_per_s"]) for r in c if r.get(f"embree_{mode}_mrays_per_s")])
                s[f"clpath_over_embree_{mode}"] = median(
                    [float(r[f"clpath_over_embree_{mode}"]) for r in c if r.get(f"clpath_over_embree_{mode}")])
            best_per_round = defaultdict(float)
            for struct, name in layouts:
                per_round = [(k, t_at.get((scene, struct, batch, k))) for k in rounds]
                per_round = [(k, r) for k, r in per_round if r]
                s[f"{name}_mrays_per_s"] = median([float(r["mrays_per_s"]) for _, r in per_round])
                s[f"{name}_builds"] = "+".join(sorted({r["build"] for _, r in per_round}))
                s[f"{name}_mismatched"] = max((int(r["mismatched"]) for _, r in per_round), default=-1)
                s[f"{name}_near_origin"] = max((int(r["near_origin"]) for _, r in per_round), default=-1)
                ratios = []
                for k, r in per_round:
                    ratios.append(float(c_at[(scene, batch, k)]["mrays_per_s"]) / float(r["mrays_per_s"]))
                    best_per_round[k] = max(best_per_round[k], float(r["mrays_per_s"]))
                # --paired: each round's median of launch-by-launch ratios, taken in one process.
                paired = [float(r["paired_ratio"]) for _, r in per_round if r.get("paired_ratio")]
                s[f"paired_over_{name}"] = median(paired)
                s[f"paired_over_{name}_min"] = min(paired, default=float("nan"))
                s[f"paired_over_{name}_max"] = max(paired, default=float("nan"))
                s[f"paired_{name}_clpath_differs"] = max((int(r["paired_clpath_differs"]) for _, r in per_round
                                                          if r.get("paired_clpath_differs")), default=-1)
                s[f"clpath_over_{name}"] = median(ratios)
                s[f"clpath_over_{name}_min"] = min(ratios, default=float("nan"))
                s[f"clpath_over_{name}_max"] = max(ratios, default=float("nan"))
            s["clpath_over_best_tinybvh"] = median(
                [float(c_at[(scene, batch, k)]["mrays_per_s"]) / v for k, v in best_per_round.items() if v > 0])
            s["load1_min"] = min(float(r["load1"]) for r in c)
            s["load1_max"] = max(float(r["load1"]) for r in c)
            summary.append(s)

    # 1 when the harness ran --paired (a paired BVH4_GPU ratio exists), for the table's extra column.
    paired_run = int(any(not math.isnan(s.get("paired_over_gpu4way", float("nan"))) for s in summary))
    keys = list(summary[0].keys())
    with open(out / "summary.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for s in summary:
            w.writerow({k: (f"{v:.4f}" if isinstance(v, float) else v) for k, v in s.items()})

    cores = int(meta.get("cores", "2"))
    shared = max(loads) > 1.5 * cores
    lines = []
    add = lines.append
    add("# Ray batches side by side: clpath against tinybvh's OpenCL kernels (and Embree)")
    add("")
    add(f"- Device: `{meta['device']}` ({meta['platform']}), {meta['cpu']}, {cores} cores; every tracer on the same "
        "OpenCL device (Embree on the same cores).")
    minutes = (datetime.datetime.strptime(meta["date_end"], "%Y-%m-%d %H:%M UTC") -
               datetime.datetime.strptime(meta["date_start"], "%Y-%m-%d %H:%M UTC")).total_seconds() / 60
    add(f"- Date: {meta['date_start']} to {meta['date_end']} (the whole run: {minutes:.0f} minutes). clpath commit: {meta['commit']}. tinybvh commit: "
        f"{meta['tinybvh_commit']} (tinybvh {meta['tinybvh_version']}), from {meta['tinybvh_origin']}.")
    if shared:
        add(f"- **The machine was shared** with other work: load average (1 min) {min(loads):.1f} to {max(loads):.1f} "
            f"on {cores} cores during the runs (`uptime` before each run, column load1 of the run files). The tracers ran "
            "back to back, interleaved, in each round, so each ratio compares runs that met about the same load; the "
            "absolute Mrays/s are below an idle machine's.")
    else:
        add(f"- Load average (1 min) {min(loads):.1f} to {max(loads):.1f} on {cores} cores during the runs.")
    add(f"- {meta['rounds']} round{'s' if meta['rounds'] != '1' else ''}; in each, per scene: `clpath bench rays SCENE --launches {meta['launches']} "
        "--save-rays DIR` (480×320 pixels × 16 samples in 4×4-pixel tiles, work-group 64, its Embree baseline and "
        "CPU check included), then the tinybvh harness on the rays just saved "
        f"(`benchmarks/rays/tinybvh/run.sh SCENE DIR --launches {meta['launches']}`). Device times from OpenCL "
        f"profiling events: one warm-up launch, then {meta['launches']} timed; Mrays/s = rays / mean kernel time "
        "for both (Embree: wall clock of each pass). The tables give the median of the rounds; each ratio is the "
        "median of the rounds' ratios.")
    add("- **Paired**: the harness also ran clpath's own batch kernels (the program and buffers `--save-rays` "
        "wrote) in its process, turn about with tinybvh's, launch by launch, which goes first alternating; the "
        "ratio is each round's median of the launches' ratios (clpath's speed over tinybvh's), then the median "
        "of the rounds. The separate-process ratios beside them compare two programs run one after the other, "
        "which a machine whose speed drifts between runs can bias; the paired ones do not depend on that.")
    add("- tinybvh's trees: every layout built with BuildHQ and with Build, each traced; per round and batch the "
        "faster counts (the build beside each figure). Embree: its default mode (as its users run it) and robust "
        "mode (watertight, the like-for-like guarantee), both from `clpath bench rays`.")
    add("")
    head = "| scene | batch | rays | clpath Mrays/s | " + " | ".join(
        f"tinybvh {s} ({n}) Mrays/s" for s, n in layouts) + " | Embree default Mrays/s | Embree robust Mrays/s | " \
        "clpath / tinybvh BVH4_GPU (rounds' range) | clpath / best tinybvh | clpath / Embree default | clpath / Embree robust |"
    head += " clpath / tinybvh BVH4_GPU, paired (rounds' range) |" if paired_run else ""
    add(head)
    add("|" + "---|" * 3 + "---:|" * (len(layouts) + 7 + paired_run))
    for s in summary:
        cells = [s["scene"] + f" ({int(s['triangles']):,} tris)", s["batch"], f"{int(s['rays']):,}",
                 fmt(s["clpath_mrays_per_s"])]
        cells += [fmt(s[f"{n}_mrays_per_s"]) + f" ({s[f'{n}_builds']})" for _, n in layouts]
        # The rounds' spread beside the median: on a machine whose speed drifts it says how far one ratio is from the next.
        spread = f" ({fmt(s['clpath_over_gpu4way_min'])}–{fmt(s['clpath_over_gpu4way_max'])})" \
            if s.get("rounds", 1) > 1 and "clpath_over_gpu4way_min" in s else ""
        cells += [fmt(s["embree_default_mrays_per_s"]), fmt(s["embree_robust_mrays_per_s"]),
                  fmt(s.get("clpath_over_gpu4way", float("nan"))) + spread, fmt(s["clpath_over_best_tinybvh"]),
                  "**" + fmt(s["clpath_over_embree_default"]) + "**", fmt(s["clpath_over_embree_robust"])]
        if paired_run:
            pspread = f" ({fmt(s['paired_over_gpu4way_min'])}–{fmt(s['paired_over_gpu4way_max'])})" \
                if s.get("rounds", 1) > 1 else ""
            cells.append("**" + fmt(s.get("paired_over_gpu4way", float("nan"))) + "**" + pspread)
        add("| " + " | ".join(cells) + " |")
    add("")
    add("Hits against clpath's (most mismatched rays in any round; clpath's own column: against its double-precision "
        "CPU walk over 262,144 rays per batch, the other columns: every ray against clpath's saved hit; \"at the "
        "origin\": tinybvh hit the surface the ray leaves, within 1e-4 of its origin, see below):")
    add("")
    add("| scene | batch | clpath vs CPU | " + " | ".join(f"tinybvh {s} vs clpath" for s, _ in layouts) + " |")
    add("|---|---|" + "---:|" * (len(layouts) + 1))
    for s in summary:
        def cell(n):
            m, o = s[f"{n}_mismatched"], s[f"{n}_near_origin"]
            return f"{m} ({o} at the origin)" if o > 0 else str(m)
        add(f"| {s['scene']} | {s['batch']} | {s['clpath_mismatched']} | " + " | ".join(cell(n) for _, n in layouts) + " |")
    if paired_run:
        differs = max(s[f"paired_{n}_clpath_differs"] for s in summary for _, n in layouts)
        add("")
        add(f"Paired runs: clpath's kernels, rebuilt in the harness from what `--save-rays` wrote, gave answers "
            f"differing from the ones clpath saved for {differs} rays (at most, over all rounds, batches and layouts; "
            "the same kernels on the same device must give 0).")
    add("")
    add(Path(meta["notes"]).read_text().rstrip("\n"))
    add("")
    (out / "README.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
