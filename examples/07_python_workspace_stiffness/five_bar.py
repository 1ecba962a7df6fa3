#!/usr/bin/python3
"""Stiffness map of a planar five-bar parallel manipulator, computed in process with beamfea.

    /usr/bin/python3 examples/07_python_workspace_stiffness/five_bar.py [--quick] [--jobs N] [--no-plot]

For every point P of a grid over the workspace:
1. inverse kinematics in Python: the elbows C1, C2 on the circles of the proximal links (elbows
   out), the working mode with both distal links meeting at P;
2. the model as a dict: four aluminium beams, two actuated revolute joints with springs k at the
   base, three passive revolute joints (elbows and the platform), the base held;
3. beamfea.run(model) -> the 6x6 Cartesian stiffness of P (the "stiffness" analysis), a NumPy
   array; the stiffness index is the weakest in-plane translational stiffness (the platform free
   to rotate): the smallest eigenvalue of inv(C[:2, :2]), C = inv(K);
4. the check: with rigid links the compliance would be C_rigid = J diag(1/k) J^T (J = dP/dtheta,
   the five-bar's forward Jacobian); the beams only add compliance, so the computed index must
   stay at or below the rigid-link one everywhere. The poses run on a thread pool (the engine
   releases the GIL).
Writes out/stiffness_map.png (unless --no-plot) and prints the summary.
"""
import argparse
import math
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from find_beamfea import import_beamfea  # noqa: E402

beamfea = import_beamfea()

A1, A2 = np.array([-0.15, 0.0]), np.array([0.15, 0.0])  # base joints [m]
L1, L2 = 0.30, 0.35        # proximal and distal link lengths [m]
K_ACT = 500.0              # actuator joint springs [N m/rad]
E_AL, NU_AL = 70e9, 0.33   # aluminium [Pa]
B_SEC, H_SEC = 0.012, 0.02 # link section b x h [m] (h in the plane of motion)


def elbow(a, p, outward):
    """Elbow C with |C - a| = L1 and |P - C| = L2 on the side `outward` (-1 left, +1 right); None
    when P is out of reach of this limb."""
    d = np.linalg.norm(p - a)
    if d > L1 + L2 or d < abs(L1 - L2) or d == 0:
        return None
    t = (L1**2 - L2**2 + d**2) / (2 * d)
    h = math.sqrt(max(L1**2 - t**2, 0.0))
    m = a + t * (p - a) / d
    n = np.array([-(p - a)[1], (p - a)[0]]) / d
    c1, c2 = m + h * n, m - h * n
    return c1 if (c1[0] - c2[0]) * outward > 0 else c2


def xyz(v):
    return [float(v[0]), float(v[1]), 0.0]


def model(p):
    """The five-bar at platform position p as a beamfea model dict, or None if unreachable."""
    c1, c2 = elbow(A1, p, -1), elbow(A2, p, +1)
    if c1 is None or c2 is None:
        return None
    nodes = [("G1", A1), ("B1", A1), ("C1a", c1), ("C1b", c1), ("P", p),
             ("G2", A2), ("B2", A2), ("C2a", c2), ("C2b", c2), ("P2", p)]

    def beam(i, a, b):
        return {"id": i, "type": "beam", "nodes": [a, b], "material": "al", "section": "link"}

    def revolute(i, a, b, k=None):
        j = {"id": i, "type": "revolute", "nodes": [a, b], "axes": [[0, 0, 1]]}
        if k is not None:
            j["stiffness"] = [k]
        return j

    return {
        "title": "planar five-bar at P = (%.3f, %.3f)" % (p[0], p[1]),
        "nodes": [{"id": n, "xyz": xyz(v)} for n, v in nodes],
        "materials": [{"id": "al", "E": E_AL, "nu": NU_AL}],
        "sections": [{"id": "link", "shape": "rectangle", "b": B_SEC, "h": H_SEC}],
        "elements": [beam("prox1", "B1", "C1a"), beam("dist1", "C1b", "P"),
                     beam("prox2", "B2", "C2a"), beam("dist2", "C2b", "P2")],
        "joints": [revolute("q1", "G1", "B1", K_ACT), revolute("q2", "G2", "B2", K_ACT),
                   revolute("e1", "C1a", "C1b"), revolute("e2", "C2a", "C2b"), revolute("p", "P", "P2")],
        "supports": [{"node": "G1", "fix": "all"}, {"node": "G2", "fix": "all"}],
        "analyses": [{"id": "K", "type": "stiffness", "node": "P"}],
    }


def rigid_link_index(p):
    """Weakest in-plane stiffness with rigid links: K = inv(J diag(1/k) J^T), J = A^-1 B from
    (P - C_i) . dP = (P - C_i) . dC_i/dtheta_i dtheta_i (differentiated loop-closure equations)."""
    rows, diag = [], []
    for a, side in ((A1, -1), (A2, +1)):
        c = elbow(a, p, side)
        r = p - c
        dc = np.array([-(c - a)[1], (c - a)[0]])  # dC/dtheta = L1 (-sin, cos)
        rows.append(r)
        diag.append(r @ dc)
    A, B = np.array(rows), np.diag(diag)
    if abs(np.linalg.det(A)) < 1e-9 * L2**2:
        return 0.0  # type II singularity (distal links aligned)
    J = np.linalg.solve(A, B)
    C = J @ J.T / K_ACT
    return 1.0 / np.linalg.eigvalsh(C)[-1]


def index(res):
    a = res["analyses"]["K"]
    if a.get("status") != "ok":
        return float("nan")
    C = np.linalg.inv(a["matrix"])
    return float(np.linalg.eigvalsh(np.linalg.inv(C[:2, :2]))[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="a coarse 9 x 7 grid (the test suite's run)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count())
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--out", default=os.path.join(HERE, "out"))
    args = ap.parse_args()
    nx, ny = (9, 7) if args.quick else (61, 46)
    xs, ys = np.linspace(-0.3, 0.3, nx), np.linspace(0.15, 0.6, ny)
    grid = [(i, j, np.array([x, y])) for j, y in enumerate(ys) for i, x in enumerate(xs)]
    models = [(i, j, model(p), p) for i, j, p in grid]
    todo = [(i, j, m, p) for i, j, m, p in models if m is not None]

    t0 = time.perf_counter()
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        results = list(pool.map(lambda t: beamfea.run(t[2]), todo))
    wall = time.perf_counter() - t0

    kmin = np.full((ny, nx), np.nan)
    worst_ratio, failed = 0.0, 0
    for (i, j, _, p), res in zip(todo, results):
        k = index(res)
        failed += math.isnan(k)
        kmin[j, i] = k
        kr = rigid_link_index(p)
        if kr > 0 and not math.isnan(k):
            worst_ratio = max(worst_ratio, k / kr)
    print(f"{len(todo)} reachable poses of {len(grid)} ({failed} failed), {wall:.2f} s on {args.jobs} threads "
          f"({len(todo) / wall:.0f} poses/s)")
    print(f"weakest in-plane stiffness {np.nanmin(kmin):.4g} .. {np.nanmax(kmin):.4g} N/m")
    print(f"largest ratio to the rigid-link value: {worst_ratio:.4f} (must be <= 1)")
    if worst_ratio > 1.0 + 1e-9 or failed:
        sys.exit("check failed")
    if not args.no_plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        os.makedirs(args.out, exist_ok=True)
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        im = ax.pcolormesh(xs, ys, np.log10(kmin), shading="nearest", cmap="viridis")
        fig.colorbar(im, ax=ax, label="log10 weakest in-plane stiffness [N/m]")
        ax.plot(*zip(A1, A2), "ks", ms=6)
        ax.set(xlabel="x [m]", ylabel="y [m]", aspect="equal",
               title="five-bar: stiffness index over the workspace")
        fig.tight_layout()
        path = os.path.join(args.out, "stiffness_map.png")
        fig.savefig(path, dpi=80)
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
