#!/usr/bin/env python3
"""Plots of `clpath bench convergence` CSV: MSE against samples per pixel and
against render time, log-log, one line per estimator configuration, with a
1/N reference line (an unbiased Monte Carlo estimator's MSE falls as 1/N; a
biased one flattens out at its squared bias) and the 30/35/40 dB levels.

    plot_convergence.py convergence.csv OUT.png [--title TEXT]
"""
import argparse
import csv
import math
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    series = OrderedDict()
    with open(path, newline="") as f:
        rows = csv.DictReader(f)
        need = {"scene", "config", "spp", "seconds", "mse", "psnr"}
        if not need.issubset(rows.fieldnames or []):
            sys.exit("%s: expected columns %s, got %s" % (path, sorted(need), rows.fieldnames))
        for r in rows:
            s = series.setdefault(r["config"], {"spp": [], "seconds": [], "mse": []})
            s["spp"].append(int(r["spp"]))
            s["seconds"].append(float(r["seconds"]))
            s["mse"].append(float(r["mse"]))
            scene = r["scene"]
    if not series:
        sys.exit(path + ": no data rows")
    return scene, series


def main():
    p = argparse.ArgumentParser()
    p.add_argument("csv")
    p.add_argument("out")
    p.add_argument("--title", default=None)
    a = p.parse_args()
    scene, series = read(a.csv)

    fig, (ax_n, ax_t) = plt.subplots(1, 2, figsize=(12, 4.8))
    for name, s in series.items():
        ax_n.loglog(s["spp"], s["mse"], marker="o", ms=3, label=name)
        ax_t.loglog(s["seconds"], s["mse"], marker="o", ms=3, label=name)
    # The 1/N line through the last configuration's first point (clpath's
    # default comes last in the standard list).
    ref = list(series.values())[-1]
    n0, m0, t0 = ref["spp"][0], ref["mse"][0], ref["seconds"][0]
    n_max = max(max(s["spp"]) for s in series.values())
    t_all = [t for s in series.values() for t in s["seconds"]]
    ax_n.loglog([n0, n_max], [m0, m0 * n0 / n_max], "k--", lw=1, label="1/N")
    ax_t.loglog([t0, max(t_all)], [m0, m0 * t0 / max(t_all)], "k--", lw=1, label="1/t")
    for ax in (ax_n, ax_t):
        for db in (30, 35, 40):
            ax.axhline(10 ** (-db / 10), color="grey", lw=0.6, ls=":")
            ax.text(ax.get_xlim()[0], 10 ** (-db / 10), " %d dB" % db, va="bottom", fontsize=7, color="grey")
        ax.set_ylabel("MSE against the reference")
        ax.grid(True, which="major", alpha=0.3)
    ax_n.set_xlabel("samples per pixel")
    ax_t.set_xlabel("render time (s)")
    ax_t.legend(fontsize=8, loc="lower left")
    fig.suptitle(a.title or ("Convergence of %s" % scene))
    fig.tight_layout()
    tmp = a.out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, a.out)
    print("wrote " + a.out)


if __name__ == "__main__":
    main()
