#!/usr/bin/env python3
"""Paper estimate of what one 4K frame costs to merge over MPI ranks.

Each rank sends its film once, at the end: 3 channels per pixel of 16-byte
fixed-point sums (clpath's exact film; 3 doubles would be 24 bytes a pixel).
Two models of MPI_Reduce of M bytes over P ranks on a network of B bytes/s:
a binomial tree, ceil(log2 P) steps of M/B, and a reduce-scatter + gather
(Rabenseifner 2004), about 2 (P-1)/P M/B whatever P. Latency and the
reduction's own arithmetic are left out (microseconds, and memory speed).
Chunk requests are 24-byte messages, one per chunk of samples: negligible.
"""
import math

WIDTH, HEIGHT, CHANNELS = 3840, 2160, 3
BYTES = {"16-byte fixed point (clpath)": 16, "8-byte double": 8}
NETWORKS = {"10 Gbit/s": 10e9 / 8, "100 Gbit/s": 100e9 / 8}
RANKS = [2, 4, 16, 64, 256, 1024]

print("Merging one 3840x2160 frame (seconds, once per render):\n")
for label, size in BYTES.items():
    m = WIDTH * HEIGHT * CHANNELS * size
    print(f"{label}: {m / 1e6:.0f} MB per rank\n")
    print("| ranks | " + " | ".join(f"tree, {n} | reduce-scatter, {n}" for n in NETWORKS) + " |")
    print("|--:|" + "--:|" * (2 * len(NETWORKS)))
    for p in RANKS:
        cells = []
        for bw in NETWORKS.values():
            cells.append(f"{math.ceil(math.log2(p)) * m / bw:.2f}")
            cells.append(f"{2 * (p - 1) / p * m / bw:.2f}")
        print(f"| {p} | " + " | ".join(cells) + " |")
    print()
