#!/usr/bin/python3
"""Bu (2012) planar parallel manipulator as a lumped (VJM) model, driven by platform positions.

    /usr/bin/python3 examples/10_bu_platform_poses/platform_poses.py [--no-plots]

One model, one reference geometry (the platform at P1 = (0, 1.1), horizontal); every other pose is a
`pose.nodes` target on the platform node P (position and orientation). beamfea solves the actuator
coordinates, every passive joint follows, the loop closes, and the analyses run about the posed
geometry. For both of the paper's actuator allocations (J1 J2 J3 and J1 J2 J6) the script

1. checks the solved joint coordinates at P1..P5 against the closed-form inverse kinematics of the
   paper's eqs. (intersection of two circles per dyad, elbows outward: docs/notes/bu_mechanism.py),
2. checks the platform compliance (phi, x, y) against J K^-1 J^T of the paper's Jacobian (eqs. 21-25),
3. runs a sweep along the line x = 0, y = 1.05 .. 1.55 through P1..P5 (a running curve, Bu's eq. 19
   evaluated along a path) and plots the stiffness indices of P along it: the stiffness along y
   (`indices.along`) and the smallest translational eigen-stiffness (`indices.translational.min`).

Writes out/poses.md, out/running_curve.csv and out/running_curve.png; exit 1 when a check fails.
"""
import argparse
import csv
import importlib.util
import os
import sys

import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
OUT = os.path.join(HERE, "out")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from find_beamfea import import_beamfea  # noqa: E402

beamfea = import_beamfea()  # an installed beamfea, or the one built in build/python

# A planar loop modelled in 3-D: three of its six closure rows are redundant, as beamfea says once per run.
warnings.filterwarnings("ignore", message=".*constraint rows are redundant.*")

spec = importlib.util.spec_from_file_location("bu_mechanism", os.path.join(ROOT, "docs", "notes", "bu_mechanism.py"))
mech = importlib.util.module_from_spec(spec)
spec.loader.exec_module(mech)

K_ACT = 1.0            # actuator stiffness; compliances come out in units of 1/k_act
Y_REF = mech.POSES["P1"]
TOL_Q = 1e-9           # rad, solved vs closed-form joint coordinates
TOL_C = 1e-9           # relative, compliance vs J K^-1 J^T (both exact for rigid links)
SCHEMES = {"J1J2J3": ("J1", "J2", "J3"), "J1J2J6": ("J1", "J2", "J6")}
# Joint nodes (proximal, distal): the first node is on the base side of each limb, so that a joint's
# coordinate is the rotation of its distal body relative to its proximal one, as in eqs. 21-22.
JOINT_NODES = {"J1": ("J1g", "J1l"), "J2": ("J2p", "J2d"), "J3": ("J3p", "J3d"),
               "J6": ("J6g", "J6l"), "J5": ("J5p", "J5d"), "J4": ("J4p", "J4d")}
LINKS = [("J1J2", "J1l", "J2p"), ("J2J3", "J2d", "J3p"), ("J3P", "J3d", "P"), ("PJ4", "P", "J4d"),
         ("J4J5", "J4p", "J5d"), ("J5J6", "J5p", "J6l")]


def xyz(p):
    return [float(p[0]), float(p[1]), 0.0]


def model(scheme, y=None):
    """The lumped model at the reference geometry P1, posed at P = (0, y) (no pose: the reference)."""
    pts = mech.ik(Y_REF)
    nodes = [{"id": n, "xyz": xyz(pts[j])} for j, pair in JOINT_NODES.items() for n in pair]
    nodes.append({"id": "P", "xyz": xyz(pts["P"])})
    act = SCHEMES[scheme]
    joints = [{"id": j, "type": "revolute", "nodes": list(pair), "axes": [[0, 0, 1]],
               "stiffness": [K_ACT if j in act else 0.0]} for j, pair in JOINT_NODES.items()]
    m = {"nodes": nodes,
         "elements": [{"id": i, "type": "rigid", "nodes": [a, b]} for i, a, b in LINKS],
         "joints": joints,
         "supports": [{"node": "J1g", "fix": "all"}, {"node": "J6g", "fix": "all"}],
         "analyses": [{"id": "K", "type": "stiffness", "node": "P", "directions": [[0, 1, 0]]}]}
    if y is not None:
        m["pose"] = {"nodes": [{"node": "P", "xyz": [0.0, float(y), 0.0], "rotation": np.eye(3).tolist()}]}
    return m


def planar_block(C):
    """(rz, ux, uy) block of a 6x6 [ux uy uz rx ry rz] matrix, in the paper's order [phi, x, y]."""
    idx = [5, 0, 1]
    return np.asarray(C)[np.ix_(idx, idx)]


def check_poses(scheme):
    """P1..P5: solved joint coordinates vs closed-form inverse kinematics, compliance vs J K^-1 J^T."""
    q_ref = mech.joint_coords(mech.ik(Y_REF))
    rows, worst_q, worst_c = [], 0.0, 0.0
    for name, y in mech.POSES.items():
        res = beamfea.run(model(scheme, y))
        q_ik = mech.joint_coords(mech.ik(y))
        err_q = max(abs(res["pose"]["joints"][j] - (q_ik["q" + j[1]] - q_ref["q" + j[1]])) for j in JOINT_NODES)
        J, _ = mech.jac_analytic(mech.ik(y), SCHEMES[scheme])
        C_ref = J @ J.T / K_ACT
        K = res["analyses"]["K"]
        C = planar_block(K["compliance"])
        err_c = np.linalg.norm(C - C_ref) / np.linalg.norm(C_ref)
        worst_q, worst_c = max(worst_q, err_q), max(worst_c, err_c)
        rows.append(f"| {scheme} | {name} | {y:.1f} | {err_q:.1e} | {err_c:.1e} | {K['indices']['along'][0]:.4f} | "
                    f"{K['indices']['translational']['min']:.4f} |")
    return rows, worst_q, worst_c


def running_curve(scheme, ys):
    """A sweep along x = 0 through P1..P5: one case per platform position (Bu's running curve)."""
    spec = {"model": model(scheme, Y_REF),
            "grid": [{"name": "y", "pointer": "/pose/nodes/0/xyz/1", "values": [float(y) for y in ys]}],
            "outputs": [{"name": "k_y", "path": "analyses.K.indices.along[0]"},
                        {"name": "k_min", "path": "analyses.K.indices.translational.min"}]}
    cols = beamfea.sweep(spec)
    return np.asarray(cols["k_y"], dtype=float), np.asarray(cols["k_min"], dtype=float)


def allocation(y):
    """The paper's question at one pose: which three of the six joints to actuate. The posed model
    (every joint passive) with an `actuator_allocation` analysis over all C(6, 3) = 20 schemes, ranked
    by the total stiffness along y (rigid links: the actuated stiffness K_A of eq. 10)."""
    m = model("J1J2J3", y)
    for j in m["joints"]:
        j["stiffness"] = [0.0]
    m["analyses"] = [{"id": "alloc", "type": "actuator_allocation", "platform_node": "P",
                      "candidate_joints": list(JOINT_NODES), "actuators": 3, "actuator_stiffness": K_ACT,
                      "directions": ["rz", "ux", "uy"], "rank_by": {"stiffness": "total", "direction": "uy"}}]
    return beamfea.run(m)["analyses"]["alloc"]


def allocation_rows():
    """Per pose: the valid schemes, the three stiffest along y, and the paper's two schemes' values."""
    md = ["", "| pose | valid schemes of 20 | stiffest along y (k_act/m^2) | J1+J2+J3 | J1+J2+J6 |", "|---|---|---|---|---|"]
    for name, y in mech.POSES.items():
        a = allocation(y)
        value = {r["scheme"]: r["worst_value"] for r in a["ranking"]}
        top = ", ".join(f"{r['scheme']} {r['worst_value']:.3f}" for r in a["ranking"][:3])
        md.append(f"| {name} | {a['valid_schemes']} | {top} | {value['J1+J2+J3']:.4f} | {value['J1+J2+J6']:.4f} |")
    return md


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--no-plots", action="store_true")
    args = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    md = ["| scheme | pose | y | joint coordinates vs closed-form IK (rad) | compliance vs J K^-1 J^T (rel.) | "
          "k along y (k_act/m^2) | smallest k (k_act/m^2) |", "|---|---|---|---|---|---|---|"]
    ok = True
    ys = np.linspace(1.05, 1.55, 51)
    curves = {}
    for scheme in SCHEMES:
        rows, wq, wc = check_poses(scheme)
        md += rows
        ok = ok and wq < TOL_Q and wc < TOL_C
        curves[scheme] = running_curve(scheme, ys)
    md += allocation_rows()
    text = "\n".join(md) + "\n"
    with open(os.path.join(OUT, "poses.md"), "w") as f:
        f.write(text)
    print(text)
    with open(os.path.join(OUT, "running_curve.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["y"] + [f"{s}_{c}" for s in SCHEMES for c in ("k_y", "k_min")])
        for i, y in enumerate(ys):
            w.writerow([f"{y:.4f}"] + [f"{curves[s][c][i]:.6g}" for s in SCHEMES for c in (0, 1)])
    if not args.no_plots:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.2))
        for s, style in zip(SCHEMES, ("-", "--")):
            ax.plot(ys, curves[s][0], "C0" + style, label=f"{s}: stiffness along y")
            ax.plot(ys, curves[s][1], "C1" + style, label=f"{s}: smallest stiffness")
        for name, y in mech.POSES.items():
            ax.axvline(y, color="0.8", lw=0.8)
            ax.text(y, 0.45, name, ha="center", fontsize=8, transform=ax.get_xaxis_transform())
        ax.set_xlabel("platform position y (m), x = 0, platform horizontal")
        ax.set_ylabel("stiffness at P (k_act / m^2)")
        ax.set_yscale("log")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(OUT, "running_curve.png"), dpi=120)
    if not ok:
        sys.exit("a check failed: see out/poses.md")


if __name__ == "__main__":
    main()
