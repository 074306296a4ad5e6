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
#   square/trajectories.csv   traj,t,x,y,theta,vx,vy,omega   (the first 0.4 s: 101 rows each)
#   square/pybullet.csv       traj,t,x,y,theta               (the same rows, poses only)
# The output is byte for byte the same on every run: impact numbers are written
# as Python's shortest round-trip repr of each double; trajectory numbers are the
# upstream values rounded to 1e-7 (m, rad, m/s, rad/s: "%.7f", trailing zeros
# dropped), far below the tracker's own scatter, which this script measures and
# prints; t = row index / 250 s. Only the rows the trajectory fit replays are
# written (t <= 0.4 s, docs/real-trajectories.md): the full 200 rows of every
# file, as upstream text, would be 26 MB.
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
ROWS = 101           # t = 0, 0.004, ..., 0.4 s: what the trajectory fit replays
DECIMALS = 7         # trajectory numbers are rounded to 1e-7 (m, rad, m/s, rad/s)
SQUARE_HALF = 0.03   # m, half the square's side (upstream README: 0.06 m)


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


def fixed(text):
    # The upstream number rounded to DECIMALS places, trailing zeros dropped.
    number(text)  # a finite number, or the conversion stops
    out = "%.*f" % (DECIMALS, float(text))
    out = out.rstrip("0").rstrip(".")
    return "0" if out in ("-0", "") else out


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


def convert_trajectories(folder, prefix, target, columns):
    # The first ROWS rows of every trajectory, its first `columns` upstream
    # fields (6: pose and velocity, 3: the pose) rounded by fixed().
    names = ["x", "y", "theta", "vx", "vy", "omega"][:columns]
    lines = ["traj,t," + ",".join(names)]
    numbers = trajectory_numbers(folder, prefix)
    poses = {}
    for n in numbers:
        path = os.path.join(folder, "%s_%d.csv" % (prefix, n))
        body = read_trajectory(path)
        if len(body) < ROWS:
            fail("%s: %d rows, the fit needs the first %d" % (path, len(body), ROWS))
        poses[n] = np.array([[float(f) for f in fields[:3]] for fields in body], dtype=np.float64)
        for i, fields in enumerate(body[:ROWS]):
            lines.append(",".join([str(n), repr(i / FRAME_RATE)] + [fixed(f) for f in fields[:columns]]))
    write(target, lines)
    return numbers, len(lines) - 1, poses


def free_flight_scatter(poses):
    # The tracker's own scatter: in free flight the pose is a parabola in
    # time (x, y) or a line (theta; a parabola fitted alike). Per recording,
    # the RMS residual of a quadratic fit to the rows before the square's
    # lowest corner first comes within 10 mm of the ground (at least 6 rows);
    # the median over the recordings, for the position (x and y) and theta.
    position, angle = [], []
    for pose in poses.values():
        x, y, th = pose[:, 0], pose[:, 1], pose[:, 2]
        corners = [y + SQUARE_HALF * (sx * np.sin(th) + sy * np.cos(th))
                   for sx in (-1, 1) for sy in (-1, 1)]
        low = np.min(corners, axis=0)
        near = np.nonzero(low < 0.01)[0]
        rows = int(near[0]) if near.size else len(low)
        if rows < 6:
            continue
        t = np.arange(rows) / FRAME_RATE
        for values, out in ((x, position), (y, position), (th, angle)):
            fit = np.polyval(np.polyfit(t, values[:rows], 2), t)
            out.append(math.sqrt(float(np.sum((values[:rows] - fit) ** 2)) / (rows - 3)))
    return len(angle), float(np.median(position)), float(np.median(angle))


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
    recorded, rows, poses = convert_trajectories(
        os.path.join(args.upstream, SQUARE), "traj",
        os.path.join(args.out, "square", "trajectories.csv"), 6)
    replayed, sim_rows, _ = convert_trajectories(
        os.path.join(args.upstream, VISUAL), "trajSim",
        os.path.join(args.out, "square", "pybullet.csv"), 3)
    if replayed != recorded:
        fail("the recorded and the PyBullet trajectories are numbered differently")
    differing = compare_copies(args.upstream, recorded)
    print("ellipse/impacts.csv: %d impacts" % impacts)
    print("square/trajectories.csv: %d trajectories, %d rows" % (len(recorded), rows))
    print("square/pybullet.csv: %d trajectories, %d rows" % (len(replayed), sim_rows))
    counted, position, angle = free_flight_scatter(poses)
    print("tracker scatter in free flight (RMS residual of a quadratic fit, median over %d "
          "recordings): %.2g m (x, y), %.2g rad (theta); the files round to %.0e"
          % (counted, position, angle, 10.0 ** -DECIMALS))
    if differing:
        print("warning: %d traj_N.csv differ between '%s' and '%s' (the first is used): %s"
              % (len(differing), SQUARE, VISUAL, differing[:10]), file=sys.stderr)
    else:
        print("the traj_N.csv copies in '%s' and '%s' are byte-identical" % (SQUARE, VISUAL))


if __name__ == "__main__":
    main()
