#!/usr/bin/env python3
"""The README of benchmarks/results/gpu-compile/ from `clpath kernels --report --csv`
output: the traversal kernels and the megakernel per target, before and after
when a second table is given. Usage:
    summarize.py resources.csv --log log.txt [--before before.csv --before-label TEXT] > README.md
"""
import argparse
import csv
import re
import sys

TARGETS = ["sm_90", "gfx90a", "gfx1100"]


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def cell(row):
    if row is None:
        return "-"
    if row["kernel"] == "FAILED":
        return "**fails**"
    regs = row["registers"]
    spills = int(row["spills"] or 0)
    return f"{regs} / {row['stack_bytes']}" + (f" / **{spills} spilled**" if spills else "")


def find(rows, program, kernel, target):
    for r in rows:
        if r["program"] == program and r["target"] == target and r["kernel"] in (kernel, "FAILED"):
            return r
    return None


def selected(rows, text, kernel, target):
    for r in rows:
        if text in r["selected_by"] and r["target"] == target and r["kernel"] in (kernel, "FAILED"):
            return r
    return None


def largest(rows, kernel, target, key):
    best = None
    for r in rows:
        if r["target"] == target and r["kernel"] == kernel:
            if best is None or int(r[key]) > int(best[key]):
                best = r
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("--log", required=True)
    ap.add_argument("--before")
    ap.add_argument("--before-label", default="before")
    a = ap.parse_args()
    after = read(a.csv)
    before = read(a.before) if a.before else None
    log = open(a.log).read()
    head = log.splitlines()[0].lstrip("= ")
    tools = re.search(r"clpath: toolchain:\n((?:[^\n]*\n)*?)(?=clpath: \[|clpath: targets)", log)
    out = sys.stdout.write

    out("# GPU compile: registers, stack and spills of every kernel program\n\n")
    out("Every OpenCL program clpath builds for a GPU device, compiled offline without a GPU by\n"
        "`clpath kernels --report` (`benchmarks/gpu-compile/run.sh`): the covering set of\n"
        "`host/render/kernel_programs.hpp` (every integrator with every feature, alpha on and off; each\n"
        "feature alone; every feature but one; the flat structure, uniform hemisphere, BSDF-only\n"
        "sampling; the wavefront of path and path-bsdf; the ray-batch programs) and the programs of\n"
        "`cornell` and every bundled scene (megakernel and wavefront).\n"
        "NVIDIA: clang-14 (nvptx64-nvidia-nvcl) + libclc + opt/llc 14 + the CUDA toolkit's `ptxas -arch=sm_90 -v`;\n"
        "AMD: clang/llc 14 (gfx90a) and 15 (gfx1100, which LLVM 14 lacks) with libclc 14's amdgcn bitcode,\n"
        "figures from the kernel descriptors. `clpath kernels --dump DIR` writes each program's source and\n"
        "options, so the same figures come from the stock tools by hand.\n\n")
    out(f"- {head}\n")
    if tools:
        for line in tools.group(1).strip().splitlines():
            out(f"- {line.strip()}\n")
    out("\nCells are registers / stack bytes (NVIDIA: registers per thread and cumulative stack frame;\n"
        "AMD: VGPRs per lane and private segment bytes per lane), and spills where there are any.\n"
        "An H100 SM has 65,536 registers: 64 per thread keep 32 warps resident, 180 only 11. The\n"
        "stack is per thread and lives in off-chip local memory.\n\n")

    def table(title, specs):
        out(f"## {title}\n\n")
        cols = []
        for t in TARGETS:
            if before:
                cols += [f"{t} {a.before_label}", f"{t} now"]
            else:
                cols.append(t)
        out("| program | kernel | " + " | ".join(cols) + " |\n")
        out("|---|---|" + "--:|" * len(cols) + "\n")
        for label, getter, kernel in specs:
            cells = []
            for t in TARGETS:
                if before:
                    cells.append(cell(getter(before, kernel, t)))
                cells.append(cell(getter(after, kernel, t)))
            out(f"| {label} | `{kernel}` | " + " | ".join(cells) + " |\n")
        out("\n")

    prog = lambda name: (lambda rows, k, t: find(rows, name, k, t))
    table("Traversal kernels (budget at sm_90: 64 registers, 256 B stack)", [
        ("ray batches, BVH", prog("rays-bvh"), "batch_trace_closest"),
        ("ray batches, BVH", prog("rays-bvh"), "batch_trace_any"),
        ("ray batches, flat list", prog("rays-flat"), "batch_trace_closest"),
        ("ray batches, flat list", prog("rays-flat"), "batch_trace_any"),
        ("ray batches, instances (two levels)", prog("rays-bvh-instances"), "batch_trace_closest"),
        ("ray batches, instances (two levels)", prog("rays-bvh-instances"), "batch_trace_any"),
    ])
    wf = lambda text: (lambda rows, k, t: selected(rows, text, k, t))
    shading = ("wf_shade", "wf_light", "wf_connect", "wf_scatter")
    specs = [("Cornell box", wf("scene cornell, wavefront"), k)
             for k in ("wf_camera", "wf_trace") + shading + ("wf_shadow", "wf_next_bounce", "wf_accumulate")]
    specs += [("Suzanne (glTF materials: budget 96)", wf("scene Suzanne, wavefront"), k) for k in shading]
    specs += [("path, every feature (glTF included)", prog("wf-path-all"), k) for k in shading]
    specs += [
        ("Cornell box, thesis (GGX conductor, dielectric)", wf("scene cornell-thesis, wavefront"), "wf_connect"),
        ("Cornell box, thesis (GGX conductor, dielectric)", wf("scene cornell-thesis, wavefront"), "wf_scatter"),
        ("path, every feature and alpha", prog("wf-path-all-alpha"), "wf_trace"),
        ("path, every feature and alpha", prog("wf-path-all-alpha"), "wf_shadow"),
        ("path-bsdf, every feature", prog("wf-path-bsdf-all"), "wf_shade"),
        ("path-bsdf, every feature", prog("wf-path-bsdf-all"), "wf_scatter"),
        ("path, diffuse alone", prog("wf-path-diffuse"), "wf_scatter"),
        ("path, flat list, every feature", prog("wf-path-flat-all"), "wf_trace"),
        ("path, diffuse, instances (two levels)", prog("wf-path-diffuse-instances"), "wf_trace"),
        ("path, diffuse, instances (two levels)", prog("wf-path-diffuse-instances"), "wf_shadow"),
    ]
    specs += [("the most registers of any program", lambda rows, k, t: largest(rows, k, t, "registers"), k)
              for k in ("wf_trace",) + shading + ("wf_shadow",)]
    table("Wavefront kernels (budget at sm_90: 64 registers, 256 B stack; the shading kernels "
          "wf_shade, wf_connect and wf_scatter with glTF materials 96)", specs)
    table("The megakernel (no budget; on GPUs the wavefront renders path and path-bsdf by default)", [
        ("Cornell box's features (diffuse, emission, triangle lights)",
         lambda rows, k, t: selected(rows, "scene cornell", k, t), "render_paths"),
        ("path, every feature", prog("path-all"), "render_paths"),
        ("path, every feature and alpha", prog("path-all-alpha"), "render_paths"),
        ("the most registers of any program", lambda rows, k, t: largest(rows, k, t, "registers"), "render_paths"),
        ("the most stack of any program", lambda rows, k, t: largest(rows, k, t, "stack_bytes"), "render_paths"),
        ("film resolve", prog("path-all"), "film_resolve"),
    ])
    over = re.findall(r"clpath: over budget: ([^\n]*)", log)
    held = re.findall(r"clpath: over budget, open: ([^\n]*)", log)
    out("## Over budget\n\n")
    if over:
        out(f"{len(over)} kernel figures over their sm_90 budget (`clpath kernels --check` fails on each):\n\n")
        for line in over:
            out(f"- {line}\n")
    else:
        out("None beyond the figures held below: `clpath kernels --check` passes.\n")
    out("\n")
    if held:
        out(f"{len(held)} kernel figures over their sm_90 budget but within the figures they are held at "
            "(`KernelBudget` in `host/render/kernel_report.cpp`; past those they fail):\n\n")
        for line in held:
            out(f"- {line}\n")
        out("\n")
    out("## Every program\n\n")
    for name, rows in (("now", after),) + ((a.before_label, before),) if before else (("now", after),):
        programs = {r["program"] for r in rows}
        failed = {(r["program"], r["target"]) for r in rows if r["kernel"] == "FAILED"}
        out(f"- {name}: {len(programs)} programs x {len(TARGETS)} targets, {len(failed)} compiles failed")
        if failed:
            names = sorted({p for p, _ in failed})
            out(" (" + ", ".join(sorted({t for _, t in failed})) + "; " + str(len(names)) + " programs, e.g. "
                + ", ".join(names[:3]) + ")")
        out("\n")
    out("\nEvery kernel of every program and target, with its build options and what selects it:\n"
        "[resources.csv](resources.csv)" + (" (before: [before.csv](before.csv))" if before else "") + ".\n")


if __name__ == "__main__":
    main()
