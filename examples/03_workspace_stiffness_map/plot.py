#!/usr/bin/python3
"""Heat map of the tip stiffness over the workspace, and a check against the joint springs.

    /usr/bin/python3 plot.py                     # runs sweep.json in process: beamfea.sweep(...)
    /usr/bin/python3 plot.py --csv out/cases.csv # plots the table of `beamfea sweep sweep.json --out out`
    /usr/bin/python3 plot.py --quick             # every 3rd angle (the test suite's run)

The table (one row per pose: theta1, theta2 in radians, K[0][0] .. K[5][5], the tip's posed
position tip[0..2], status) comes either from beamfea.sweep, in process, on sweep.json, or from
the program's CSV file; both are the same cases through the same engine. beamfea poses the arm
itself (model.json's "pose", which the sweep's grid sets): no kinematics here but the check's
rigid-link Jacobian.

K (6x6, ux uy uz rx ry rz) is the stiffness of the tip node with its rotations kept, so the
stiffness against a force alone (the tip free to rotate) is the inverse of the translational
block of the compliance K^-1. Plots, over (theta1, theta2), log10 of its component k_yy (a
vertical force at the tip) and of the smallest eigenvalue of its in-plane part: the stiffness
in the weakest direction, which depends on theta2 only (a shoulder rotation rotates it). With rigid links the tip compliance would be C = J diag(1/k1, 1/k2) J^T (J the
planar Jacobian); flexible links only add compliance, so the computed stiffness must stay
at or below the rigid-link value, and close to it where the joints dominate.
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
sys.path.insert(0, HERE)
from find_beamfea import import_beamfea  # noqa: E402

L1, L2, k1, k2 = 0.4, 0.3, 2000.0, 1000.0


def table_from_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    cols = {}
    for name in rows[0]:
        cells = [r[name] for r in rows]
        try:
            cols[name] = np.array([float(c) if c else np.nan for c in cells])
        except ValueError:
            cols[name] = cells
    return cols


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", help="the program's table (beamfea sweep sweep.json --out out -> out/cases.csv)")
    ap.add_argument("--quick", action="store_true", help="every 3rd angle, in process")
    ap.add_argument("--png", default=os.path.join(HERE, "stiffness_map.png"))
    args = ap.parse_args()
    if args.csv:
        cols = table_from_csv(args.csv)
    else:
        with open(os.path.join(HERE, "sweep.json")) as f:
            spec = json.load(f)
        spec["base"] = os.path.join(HERE, spec["base"])
        if args.quick:
            for axis in spec["grid"]:
                axis["values"] = axis["values"][::3]
        cols = import_beamfea().sweep(spec)  # a DataFrame with pandas, else a dict of NumPy columns
    r1 = np.asarray(cols["theta1"], dtype=float)
    r2 = np.asarray(cols["theta2"], dtype=float)
    t1, t2 = np.round(np.degrees(r1), 9), np.round(np.degrees(r2), 9)  # grid labels in degrees
    status = list(cols["status"])
    K_all = np.stack([np.stack([np.asarray(cols[f"K[{a}][{b}]"], dtype=float) for b in range(6)], axis=-1)
                      for a in range(6)], axis=-2)  # (cases, 6, 6)

    t1s, t2s = sorted(set(t1)), sorted(set(t2))
    kmin = np.full((len(t1s), len(t2s)), np.nan)
    kyy = np.full((len(t1s), len(t2s)), np.nan)
    worst_ratio = 0.0
    worst_tip = 0.0
    for n in range(len(status)):
        if status[n] != "ok":
            continue
        i, j = t1s.index(t1[n]), t2s.index(t2[n])
        K2 = np.linalg.inv(np.linalg.inv(K_all[n])[:2, :2])
        kmin[i, j] = np.linalg.eigvalsh(K2)[0]
        kyy[i, j] = K2[1, 1]
        # The posed tip from beamfea against the arm's geometry (links L1, L2 from the shoulder).
        tip = np.array([float(cols[f"tip[{c}]"][n]) for c in range(2)])
        a, b = r1[n], r1[n] + r2[n]
        worst_tip = max(worst_tip, np.linalg.norm(tip - [L1 * math.cos(a) + L2 * math.cos(b), L1 * math.sin(a) + L2 * math.sin(b)]))
        J = np.array([[-L1 * math.sin(a) - L2 * math.sin(b), -L2 * math.sin(b)],
                      [L1 * math.cos(a) + L2 * math.cos(b), L2 * math.cos(b)]])
        C_rigid = J @ np.diag([1 / k1, 1 / k2]) @ J.T
        if abs(np.linalg.det(J)) > 1e-3:
            K_rigid = np.linalg.inv(C_rigid)
            worst_ratio = max(worst_ratio, kmin[i, j] / np.linalg.eigvalsh(K_rigid)[0])

    ok = sum(s == "ok" for s in status)
    print(f"{ok}/{len(status)} cases ok; weakest-direction stiffness {np.nanmin(kmin):.4g} .. {np.nanmax(kmin):.4g} N/m")
    print(f"largest ratio to the rigid-link joint-spring value (away from theta2 = 0): {worst_ratio:.4f} (must be <= 1)")
    print(f"posed tip within {worst_tip:.1e} m of L1 (cos t1, sin t1) + L2 (cos(t1 + t2), sin(t1 + t2))")
    if ok != len(status) or worst_ratio > 1.0 or worst_tip > 1e-12:
        sys.exit("check failed")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), sharey=True)
    for ax, field, title in ((axes[0], kyy, "log10 k_yy [N/m]"), (axes[1], kmin, "log10 weakest-direction stiffness [N/m]")):
        im = ax.pcolormesh(t2s, t1s, np.log10(field), shading="nearest", cmap="viridis")
        ax.set_xlabel("elbow angle theta2 [deg]")
        ax.set_title(title)
        fig.colorbar(im, ax=ax)
    axes[0].set_ylabel("shoulder angle theta1 [deg]")
    fig.tight_layout()
    fig.savefig(args.png, dpi=80)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
