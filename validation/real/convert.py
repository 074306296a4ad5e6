#!/usr/bin/env python3
# Regenerates the real-impact CSV files of validation/real/ from the public
# repository DAIRLab/ImpactModeling (a checkout, or an export of one commit;
# validation/real/README.md names the commit these files came from).
#
# Reads, below UPSTREAM:
#   IRB Bound/ellipse_uniform.mat                           (MATLAB v5, bounce_array: 2000 impacts)
#   Wang/Wang-Mason Square/dice-data-processed/traj_N.csv   (500 recorded trajectories)
#   Visualize and Read Data/trajSim_N.csv                   (PyBullet's 500 replays)
#   Visualize and Read Data/traj_N.csv                      (only compared with the copy above)
# Writes, below OUT (default: the folder holding this script):
#   ellipse/impacts.csv       impact,x0,y0,theta0,vx0,vy0,omega0,x1,y1,theta1,vx1,vy1,omega1,flags
#   square/trajectories.csv   traj,t,x,y,theta,vx,vy,omega
#   square/pybullet.csv       traj,t,x,y,theta,vx,vy,omega
# The output is byte for byte the same on every run: impact numbers are written
# as Python's shortest round-trip repr of each double; trajectory numbers are the
# upstream text, copied unchanged; t = row index / 250 s.
#
# Needs Python 3 with numpy and scipy. On Debian: apt-get install python3-scipy
# (it pulls in python3-numpy). Only re-conversion needs them: nothing in the
# project reads the .mat file.
#
#   python3 validation/real/convert.py UPSTREAM [--out OUT]

import argparse
import math
import os
import re
import sys

import numpy as np
import scipy.io

MAT = os.path.join("IRB Bound", "ellipse_uniform.mat")
SQUARE = os.path.join("Wang", "Wang-Mason Square", "dice-data-processed")
VISUAL = "Visualize and Read Data"
FLAGS = ("flag_sb", "flag_en", "flag_cl", "flag_mc", "flag_de", "flag_ld")
UPSTREAM_HEADER = "x,z,th,vx,vz,vth"
FRAME_RATE = 250.0


def fail(message):
    sys.exit("convert.py: " + message)


def number(value):
    value = float(value)
    if not math.isfinite(value):
        fail("non-finite value %r" % value)
    return repr(value)


def convert_ellipse(upstream, out):
    path = os.path.join(upstream, MAT)
    bounce = scipy.io.loadmat(path)["bounce_array"]
    if bounce.shape[0] != 1:
        fail("%s: bounce_array has shape %s, expected 1 x N" % (path, bounce.shape))
    lines = ["impact,x0,y0,theta0,vx0,vy0,omega0,x1,y1,theta1,vx1,vy1,omega1,flags"]
    for i in range(bounce.shape[1]):
        entry = bounce[0, i]
        states = np.asarray(entry["states"], dtype=np.float64).ravel()
        if states.size != 12:
            fail("impact %d: %d states, expected 12" % (i, states.size))
        flags = [int(np.asarray(entry[f]).ravel()[0]) for f in FLAGS]
        if any(f not in (0, 1) for f in flags):
            fail("impact %d: a flag is not 0 or 1: %s" % (i, flags))
        combined = [int(f) for f in np.asarray(entry["flags"]).ravel()]
        if combined != flags:
            fail("impact %d: flags %s differ from flag_sb..flag_ld %s" % (i, combined, flags))
        lines.append(",".join([str(i)] + [number(s) for s in states] + ["".join(map(str, flags))]))
    write(os.path.join(out, "ellipse", "impacts.csv"), lines)
    return bounce.shape[1]


def read_trajectory(path):
    with open(path, "r", encoding="ascii", newline="") as f:
        rows = [r.rstrip("\r") for r in f.read().split("\n")]
    while rows and rows[-1] == "":
        rows.pop()
    if not rows or rows[0] != UPSTREAM_HEADER:
        fail("%s: header is not %s" % (path, UPSTREAM_HEADER))
    body = []
    for n, row in enumerate(rows[1:], start=2):
        fields = row.split(",")
        if len(fields) != 6:
            fail("%s:%d: %d fields, expected 6" % (path, n, len(fields)))
        for field in fields:
            number(field)  # the text must parse as a finite number; it is copied as it is
        body.append(fields)
    return body


def trajectory_numbers(folder, prefix):
    found = []
    for name in os.listdir(folder):
        m = re.fullmatch(prefix + r"_(\d+)\.csv", name)
        if m:
            found.append(int(m.group(1)))
    if not found:
        fail("no %s_N.csv in %s" % (prefix, folder))
    return sorted(found)


def convert_trajectories(folder, prefix, target):
    lines = ["traj,t,x,y,theta,vx,vy,omega"]
    numbers = trajectory_numbers(folder, prefix)
    for n in numbers:
        for i, fields in enumerate(read_trajectory(os.path.join(folder, "%s_%d.csv" % (prefix, n)))):
            lines.append(",".join([str(n), repr(i / FRAME_RATE)] + fields))
    write(target, lines)
    return numbers, len(lines) - 1


def compare_copies(upstream, numbers):
    differing = []
    for n in numbers:
        name = "traj_%d.csv" % n
        other = os.path.join(upstream, VISUAL, name)
        if not os.path.exists(other):
            differing.append(n)
            continue
        with open(os.path.join(upstream, SQUARE, name), "rb") as a, open(other, "rb") as b:
            if a.read() != b.read():
                differing.append(n)
    return differing


def write(path, lines):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="ascii", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description="Regenerate validation/real/*/*.csv from DAIRLab/ImpactModeling.")
    parser.add_argument("upstream", help="checkout or export of DAIRLab/ImpactModeling")
    parser.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)),
                        help="output folder (default: the folder of this script)")
    args = parser.parse_args()

    impacts = convert_ellipse(args.upstream, args.out)
    recorded, rows = convert_trajectories(os.path.join(args.upstream, SQUARE), "traj",
                                          os.path.join(args.out, "square", "trajectories.csv"))
    replayed, sim_rows = convert_trajectories(os.path.join(args.upstream, VISUAL), "trajSim",
                                              os.path.join(args.out, "square", "pybullet.csv"))
    if replayed != recorded:
        fail("the recorded and the PyBullet trajectories are numbered differently")
    differing = compare_copies(args.upstream, recorded)
    print("ellipse/impacts.csv: %d impacts" % impacts)
    print("square/trajectories.csv: %d trajectories, %d rows" % (len(recorded), rows))
    print("square/pybullet.csv: %d trajectories, %d rows" % (len(replayed), sim_rows))
    if differing:
        print("warning: %d traj_N.csv differ between '%s' and '%s' (the first is used): %s"
              % (len(differing), SQUARE, VISUAL, differing[:10]), file=sys.stderr)
    else:
        print("the traj_N.csv copies in '%s' and '%s' are byte-identical" % (SQUARE, VISUAL))


if __name__ == "__main__":
    main()
