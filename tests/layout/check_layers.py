#!/usr/bin/env python3
"""The host folders form layers, and an #include may only run down them (or
stay in its folder): util < cl, image < scene < bvh < render < mpi, bench, denoise <
viewer < cli. No folder may hold more than a third of the host code.
Usage: check_layers.py HOST_DIR. Exit 1, naming each offending include."""
import re
import sys
from pathlib import Path

LAYERS = [["util"], ["cl", "image"], ["scene"], ["bvh"], ["render"], ["mpi", "bench", "denoise"], ["viewer"], ["cli"]]
RANK = {folder: i for i, layer in enumerate(LAYERS) for folder in layer}

host = Path(sys.argv[1])
errors, lines = [], {}
for f in sorted(host.rglob("*.[ch]pp")):
    top = f.relative_to(host).parts[0]
    if top not in RANK:
        errors.append(f"{f}: folder '{top}' is in no layer (add it to {__file__})")
        continue
    text = f.read_text()
    lines[top] = lines.get(top, 0) + text.count("\n")
    for n, line in enumerate(text.splitlines(), 1):
        m = re.match(r'\s*#\s*include\s*"([a-z_]+)/', line)
        if m and m.group(1) in RANK and m.group(1) != top and RANK[m.group(1)] >= RANK[top]:
            errors.append(f"{f}:{n}: {top}/ includes {m.group(1)}/, which is not below it")
total = sum(lines.values())
for folder, n in sorted(lines.items()):
    if 3 * n > total:
        errors.append(f"host/{folder}/ holds {n} of {total} lines, over a third of the host code")
for e in errors:
    print(e)
print(f"{len(errors)} layering problems in {total} lines of host code")
sys.exit(1 if errors else 0)
