#!/usr/bin/env python3
"""Two mappings side by side: how far MuJoCo is from the reference over
time under each (docs/python.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/compare_mappings.py \
        [--scene validation/scenes/point_mass.toml] [--mappings calibrated compensated] \
        [--out mappings.png]

The scene runs with Kelvin–Voigt damping and without friction (the
README's first comparison), once per mapping; the plot is the distance
between the engines' centres of mass, ‖(x, y)_ref − (x, y)_MuJoCo‖, against
time, on a log scale. It draws with matplotlib's Agg backend (no display
needed) into --out, by default mappings.png in a new temporary directory,
and prints the path.
"""

import argparse
import os
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
import numpy as np  # noqa: E402

import contact2d  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="validation/scenes/point_mass.toml")
    parser.add_argument("--mappings", nargs=2, default=["calibrated", "compensated"])
    parser.add_argument("--out", default=None, help="PNG to write")
    args = parser.parse_args()
    out = args.out or os.path.join(tempfile.mkdtemp(prefix="contact2d-"), "mappings.png")

    scene = contact2d.Scene.load(args.scene)
    scene.contact.damping = "kelvin_voigt"
    scene.contact.mu = 0.0

    fig, ax = plt.subplots(figsize=(8, 4.5))
    for mapping in args.mappings:
        result = contact2d.compare(scene, mapping=mapping, diagnosis=False)
        ref, mj = result["ref_trajectory"], result["mujoco_trajectory"]
        n = min(len(ref), len(mj))
        x, y = contact2d.COLUMNS.index("x"), contact2d.COLUMNS.index("y")
        distance = np.hypot(ref[:n, x] - mj[:n, x], ref[:n, y] - mj[:n, y])
        # A log axis has no zero: the exact agreement of the first sample is left out.
        t = ref[:n, 0]
        keep = distance > 0
        ax.semilogy(t[keep], distance[keep],
                    label=f"{mapping}: max {result['max_pos_err']:.3g} m")
        print(f"{mapping}: max position difference {result['max_pos_err']:.4g} m "
              f"(ref to converged {result['ref_vs_converged_max_pos_err']}, "
              f"MuJoCo to converged {result['mujoco_vs_converged_max_pos_err']})")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("|ref − MuJoCo| position (m)")
    ax.set_title(f"{scene.shape}: ref vs MuJoCo, Kelvin–Voigt, μ = 0, by mapping")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print(out)


if __name__ == "__main__":
    main()
