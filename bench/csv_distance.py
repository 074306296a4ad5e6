#!/usr/bin/env python3
"""Largest distance between two trajectory CSVs of `contact2d simulate --csv`
(columns t,x,y,theta,...), row by row: max |Δ(x, y)| in m and max |Δθ| in rad.
docs/speed.md uses it for implicit Euler, one build against another.

    bench/csv_distance.py A.csv B.csv
"""
import csv
import math
import sys


def rows(path):
    with open(path, newline="") as f:
        return [list(map(float, r)) for r in list(csv.reader(f))[1:]]


a, b = rows(sys.argv[1]), rows(sys.argv[2])
pos = max((math.hypot(p[1] - q[1], p[2] - q[2]) for p, q in zip(a, b)), default=0.0)
ang = max((abs(p[3] - q[3]) for p, q in zip(a, b)), default=0.0)
print(f"rows {len(a)} {len(b)} max position {pos:.3g} m max angle {ang:.3g} rad")
