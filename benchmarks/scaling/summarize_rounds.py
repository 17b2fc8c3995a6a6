#!/usr/bin/env python3
"""Several runs of `clpath bench scaling` (one CSV each) as one table: per
size and structure, each rate's median over the runs and its coefficient of
variation (sample standard deviation over the mean, in percent), and per
batch how far the rate falls from 10^3 to the largest size measured.

    summarize_rounds.py OUT_CSV OUT_MD round1.csv round2.csv ...

OUT_CSV keeps bench scaling's columns, every number the median over the
runs (what plot_scaling.py reads); OUT_MD is the table with the variation.
Python 3 standard library only.
"""
import csv
import statistics
import sys

RATES = [("primary_mrays_per_s", "primary"), ("shadow_mrays_per_s", "shadow"),
         ("diffuse_mrays_per_s", "diffuse"), ("path_msamples_per_s", "path samples"),
         ("path_mrays_per_s", "path rays")]
# Embree's default mode on the BVH rows' batches (0 where it did not run: flat rows, a build without Embree).
EMBREE = [("embree_primary_mrays_per_s", "primary"), ("embree_shadow_mrays_per_s", "shadow"),
          ("embree_diffuse_mrays_per_s", "diffuse")]
CV_LIMIT = 5.0  # percent: a batch stable enough to compare across sizes


def cv(values):
    m = statistics.mean(values)
    return 100.0 * statistics.stdev(values) / m if len(values) > 1 and m > 0 else 0.0


def main():
    out_csv, out_md, inputs = sys.argv[1], sys.argv[2], sys.argv[3:]
    if len(inputs) < 2:
        sys.exit("summarize_rounds.py: give at least two runs' CSV files")
    runs = [list(csv.DictReader(open(f))) for f in inputs]
    header = list(runs[0][0].keys())
    keys = [(r["triangles"], r["accel"]) for r in runs[0]]
    by_key = [{(r["triangles"], r["accel"]): r for r in run} for run in runs]
    medians, table = [], []
    for key in keys:
        rows = [b[key] for b in by_key if key in b and not b[key]["skipped"]]
        if len(rows) < len(runs):  # skipped (or missing) in some run: reported as the first run has it
            first = by_key[0][key]
            medians.append(first)
            table.append((key, None, first["skipped"] or "not measured in every run"))
            continue
        med = dict(rows[0])
        stats = {}
        for col in header:
            try:
                values = [float(r[col]) for r in rows]
            except ValueError:
                continue
            if col in ("triangles", "requested", "nodes", "checked_rays", "mismatched", "embree_mismatched"):
                med[col] = rows[0][col] if not col.endswith("mismatched") else str(int(sum(values)))
                continue
            med[col] = "%.6g" % statistics.median(values)
            stats[col] = (statistics.median(values), cv(values))
        medians.append(med)
        table.append((key, stats, ""))
    with open(out_csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=header)
        w.writeheader()
        w.writerows(medians)

    embree_cols = [e for e in EMBREE if e[0] in header]
    lines = ["| triangles | structure | build ms (CV) | " +
             " | ".join("%s %s (CV)" % (name, "Msamples/s" if "samples" in name else "Mrays/s") for _, name in RATES) +
             "".join(" | Embree %s (CV)" % name for _, name in embree_cols) +
             " |", "|---:|---|---:|" + "---:|" * (len(RATES) + len(embree_cols))]
    unstable = []
    for (tris, accel), stats, why in table:
        if stats is None:
            lines.append("| %s | %s | %s |%s" % (tris, accel, why, " |" * (len(RATES) + len(embree_cols))))
            continue
        cells = []
        for col, name in [("build_ms", "build")] + RATES:
            m, c = stats[col]
            flag = c >= CV_LIMIT and col != "build_ms"
            if flag:
                unstable.append("%s %s %s (%.1f %%)" % (tris, accel, name, c))
            cells.append(("**%.4g (%.1f %%)**" if flag else "%.4g (%.1f %%)") % (m, c))
        for col, _ in embree_cols:  # blank where Embree did not run; its variation is shown, not flagged
            m, c = stats.get(col, (0.0, 0.0))
            cells.append("%.4g (%.1f %%)" % (m, c) if m > 0 else "")
        lines.append("| %s | %s | %s |" % (tris, accel, " | ".join(cells)))
    lines.append("")
    lines.append("Medians of %d runs; CV: the runs' standard deviation over their mean (bold: %g %% or more)." %
                 (len(runs), CV_LIMIT))
    lines.append("Unstable entries: " + ("; ".join(unstable) if unstable else "none") + ".")
    # How far each batch falls from the size nearest 10^3 to the largest measured (BVH).
    bvh = [(int(k[0]), s) for k, s, _ in table if k[1] == "bvh" and s is not None]
    if bvh:
        lo = min(bvh, key=lambda e: abs(e[0] - 1000))
        hi = max(bvh, key=lambda e: e[0])
        lines.append("")
        lines.append("BVH, from %d to %d triangles, each rate's fall (rate at %d over the lowest rate at any size "
                     "from %d up):" % (lo[0], hi[0], lo[0], lo[0]))
        lines.append("")
        for col, name in RATES:
            lowest = min(s[col][0] for n, s in bvh if n >= lo[0])
            lines.append("- %s: %.2fx (%.4g to %.4g)" % (name, lo[1][col][0] / lowest, lo[1][col][0], lowest))
        ran = [col for col, _ in EMBREE if all(col in s and s[col][0] > 0 for n, s in bvh if n >= lo[0])]
        if ran:
            lines.append("")
            lines.append("Embree (default mode, every core) on the same rays, the same way: its fall, and clpath's rate "
                         "over Embree's at %d and at %d triangles:" % (lo[0], hi[0]))
            lines.append("")
            for col, name in EMBREE:
                if col not in ran:
                    continue
                lowest = min(s[col][0] for n, s in bvh if n >= lo[0])
                own = col[len("embree_"):]
                lines.append("- %s: %.2fx (%.4g to %.4g); clpath/Embree %.3f at %d, %.3f at %d" %
                             (name, lo[1][col][0] / lowest, lo[1][col][0], lowest,
                              lo[1][own][0] / lo[1][col][0], lo[0], hi[1][own][0] / hi[1][col][0], hi[0]))
    with open(out_md, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
