#!/usr/bin/env python3
"""Plots of `clpath bench scaling` results (the CSV its --csv writes):
rays_vs_triangles.png: log-log Mrays/s of the primary, shadow and diffuse
batches against triangles, for the BVH and the flat structure;
build_time.png: structure build time against triangles.
Usage: plot_scaling.py SCALING_CSV OUT_DIR"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if not r["skipped"]]
    if not rows:
        sys.exit(f"{path}: no measured rows")
    return rows, rows[0]["device"]


def series(rows, accel, column):
    pts = [(int(r["triangles"]), float(r[column])) for r in rows
           if r["accel"] == accel and column in r and float(r[column] or 0) > 0]
    return [p[0] for p in pts], [p[1] for p in pts]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows, device = load(sys.argv[1])
    out = sys.argv[2]
    styles = {"bvh": "-", "flat": "--"}
    colours = {"primary": "tab:blue", "shadow": "tab:orange", "diffuse": "tab:green"}

    fig, ax = plt.subplots(figsize=(7, 5))
    for accel, ls in styles.items():
        for batch, c in colours.items():
            x, y = series(rows, accel, f"{batch}_mrays_per_s")
            if x:
                ax.plot(x, y, ls, marker="o", color=c, label=f"{accel} {batch}")
    # Embree's default mode on the BVH rows' rays (CSVs from before it had a column have none).
    for batch, c in colours.items():
        x, y = series(rows, "bvh", f"embree_{batch}_mrays_per_s")
        if x:
            ax.plot(x, y, ":", marker="x", color=c, label=f"Embree {batch}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("triangles")
    ax.set_ylabel("million rays per second")
    ax.set_title(f"Ray batches against scene size\n{device}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")
    fig.tight_layout()
    fig.savefig(f"{out}/rays_vs_triangles.png", dpi=110)

    fig, ax = plt.subplots(figsize=(7, 5))
    for accel, ls in styles.items():
        x, y = series(rows, accel, "build_ms")
        if x:
            ax.plot(x, y, ls, marker="o", label=f"{accel} build")
    x, y = series(rows, "bvh", "generate_ms")
    if x:
        ax.plot(x, y, ":", marker=".", color="grey", label="scene generation")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("triangles")
    ax.set_ylabel("milliseconds (host)")
    ax.set_title("Acceleration structure build time against scene size")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")
    fig.tight_layout()
    fig.savefig(f"{out}/build_time.png", dpi=110)
    print(f"plot_scaling.py: wrote {out}/rays_vs_triangles.png and {out}/build_time.png")


if __name__ == "__main__":
    main()
