#!/usr/bin/python3
"""Bu (2012) planar manipulator as a lumped (VJM) model: a closed loop of rigid links and revolute
joints, actuator springs at J1 J2 J3, analysed with exact loop closures.

    /usr/bin/python3 examples/02_bu_planar_manipulator/bu_lumped.py [--beamfea PATH]

1. The same geometry as bu_example.py (P = (0, y), y = 1.1 .. 1.5, platform horizontal, both elbows
   outward), taken from the independent reference docs/notes/bu_reference.py (inverse kinematics and
   the paper's Jacobian J123, eqs. 21-25).
2. For every pose, out/lumped_<pose>.json: rigid links J1J2, J2J3, J3-P-J4 (the platform), J4J5,
   J5J6, revolute joints about z at J1..J6 (J1 J2 J3 with k_act = 1, the others passive), the base
   nodes of J1 and J6 fixed. The loop closes through the ground, in 3-D: three of its six closure
   rows are redundant (planar loop), which beamfea reports as statically indeterminate.
   Analysis `K`: "stiffness" of the platform node P.
3. Its compliance in (rz, ux, uy) must equal J K^-1 J^T (K = k_act I) of the paper's Jacobian.
4. At P1, analysis `loaded`: a "path" under a growing load at P (force (0.1, -0.2) k_act/m and moment
   0.03 k_act, load factor 0 .. 1 in 10 increments) with "stiffness_node": "P": the loaded compliance
   along the path, compared with the derivative of the exact equilibrium solved here
   (k_act (q - q0) = J(q)^T w for the serial left chain J1 J2 J3, which alone carries the load when
   J4 J5 J6 are passive), by central differences in the load.
Writes out/lumped_tables.md and prints it; exit 1 when a check fails.
"""
import argparse
import importlib.util
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "out")
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
K_ACT = 1.0
WRENCH = np.array([0.03, 0.1, -0.2])  # [moment, Fx, Fy] at P, the load at load factor 1
TOL_UNLOADED = 1e-9                  # relative, compliance vs J K^-1 J^T (both exact)
TOL_LOADED = 1e-6                    # relative, vs central differences of the exact equilibrium

spec = importlib.util.spec_from_file_location("bu_reference", os.path.join(ROOT, "docs", "notes", "bu_reference.py"))
ref = importlib.util.module_from_spec(spec)
sys.argv_saved, sys.argv = sys.argv, [sys.argv[0], "--quiet"]
spec.loader.exec_module(ref)  # defines functions only; main() runs under __main__
sys.argv = sys.argv_saved


def xyz(p):
    return [float(p[0]), float(p[1]), 0.0]


def lumped_model(pts, loaded):
    nodes, joints = [], []
    for j in ref.JOINTS:
        nodes += [{"id": j + "a", "xyz": xyz(pts[j])}, {"id": j + "b", "xyz": xyz(pts[j])}]
        joints.append({"id": j, "type": "revolute", "nodes": [j + "a", j + "b"], "axes": [[0, 0, 1]],
                       "stiffness": [K_ACT if j in ("J1", "J2", "J3") else 0.0]})
    nodes.append({"id": "P", "xyz": xyz(pts["P"])})
    links = [("J1J2", "J1b", "J2a"), ("J2J3", "J2b", "J3a"), ("J3P", "J3b", "P"), ("PJ4", "P", "J4a"),
             ("J4J5", "J4b", "J5a"), ("J5J6", "J5b", "J6a")]
    m = {"nodes": nodes,
         "elements": [{"id": i, "type": "rigid", "nodes": [a, b]} for i, a, b in links],
         "joints": joints,
         "supports": [{"node": "J1a", "fix": "all"}, {"node": "J6b", "fix": "all"}],
         "loads": [],
         "analyses": [{"id": "K", "type": "stiffness", "node": "P"}]}
    if loaded:
        m["loads"] = [{"node": "P", "force": [float(WRENCH[1]), float(WRENCH[2]), 0.0], "moment": [0.0, 0.0, float(WRENCH[0])]}]
        m["analyses"].append({"id": "loaded", "type": "path", "track": ["P"], "stiffness_node": "P",
                              "control": {"load_factor": 1.0, "increments": 10}})
    return m


def fmt_mat(m):
    return "[" + "; ".join(" ".join(f"{v:+.4f}" for v in row) for row in np.asarray(m)) + "]"


def planar_block(C):
    """(rz, ux, uy) block of a 6x6 [ux uy uz rx ry rz] matrix, in the paper's order [phi, x, y]."""
    idx = [5, 0, 1]
    return np.array(C)[np.ix_(idx, idx)]


def left_jacobian(q):
    """d[phi, Px, Py]/dq of the serial chain J1 J2 J3 (pose ref.fk_123(q)): the columns of the paper's
    eq. 21, [1, -r_y, r_x] with r = P - J_i at the current joint positions."""
    a1, a2 = q[0], q[0] + q[1]
    J1 = ref.BASE_J1
    J2 = J1 + ref.L12 * ref.e(a1)
    J3 = J2 + ref.L23 * ref.e(a2)
    P = J3 + ref.L3P * ref.e(a2 + q[2])
    return np.column_stack([[1.0, -(P - J)[1], (P - J)[0]] for J in (J1, J2, J3)])


def left_chain_equilibrium(q0, w):
    """k (q - q0) = J(q)^T w for the serial chain J1 J2 J3 (pose = ref.fk_123(q)); Newton with a
    central-difference Hessian of the analytic Jacobian. Valid while the passive dyad J4 J5 J6 can
    follow the platform (|J4 J6| between L45 - L56 = 0.4 and L45 + L56 = 1.6)."""
    jac = left_jacobian

    def res(q):
        return K_ACT * (q - q0) - jac(q).T @ w

    q = q0.copy()
    for _ in range(50):
        r = res(q)
        if np.linalg.norm(r) < 1e-13:
            break
        H = np.column_stack([(res(q + 1e-6 * e) - res(q - 1e-6 * e)) / 2e-6 for e in np.eye(3)])
        q = q - np.linalg.solve(H, r)
    return q


def loaded_compliance(q0, w, h=1e-4):
    """d pose / d w of the exact equilibrium, by central differences."""
    cols = []
    for e in np.eye(3):
        cols.append((ref.fk_123(*left_chain_equilibrium(q0, w + h * e)) - ref.fk_123(*left_chain_equilibrium(q0, w - h * e))) / (2 * h))
    return np.column_stack(cols)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--beamfea", default=None, help="path of the beamfea executable")
    args = ap.parse_args()
    exe = args.beamfea
    for b in ["build", "build-release"]:
        cand = os.path.join(ROOT, b, "cli", "beamfea")
        if exe is None and os.path.exists(cand):
            exe = cand
    if exe is None:
        sys.exit("beamfea executable not found: build it or pass --beamfea")
    os.makedirs(OUT, exist_ok=True)
    md = ["## Lumped model: platform compliance vs J K^-1 J^T (units 1/k_act; order phi, x, y)\n",
          "| pose | compliance (beamfea) | J K^-1 J^T (paper's J) | rel. error | rank | rigid directions | statically indeterminate rows |",
          "|---|---|---|---|---|---|---|"]
    worst_unloaded, worst_loaded = 0.0, 0.0
    loaded_rows = []
    for pose, y in ref.POSES.items():
        pts = ref.ik(y)
        J, _ = ref.jac_analytic(pts, ("J1", "J2", "J3"))
        C_ref = J @ J.T / K_ACT
        d = os.path.join(OUT, "lumped_" + pose)
        path = d + ".json"
        with open(path, "w") as f:
            json.dump(lumped_model(pts, pose == "P1"), f, indent=1)
        subprocess.run([exe, "run", path, "--out", d, "--no-vtk", "--quiet"], check=True)
        with open(os.path.join(d, "results.json")) as f:
            res = json.load(f)["analyses"]
        K = res["K"]
        C = planar_block(K["compliance"])
        err = np.linalg.norm(C - C_ref) / np.linalg.norm(C_ref)
        worst_unloaded = max(worst_unloaded, err)
        md.append(f"| {pose} | {fmt_mat(C)} | {fmt_mat(C_ref)} | {err:.1e} | "
                  f"{K['rank']} | {len(K['rigid_directions'])} | {len(K.get('statically_indeterminate', []))} |")
        if pose == "P1":
            q = ref.joint_coords(pts)
            q0 = np.array([q["q1"], q["q2"], q["q3"]])
            for st in res["loaded"]["steps"]:
                lf = st["load_factor"]
                Cb = planar_block(st["compliance"])
                Cx = loaded_compliance(q0, lf * WRENCH)
                e = np.linalg.norm(Cb - Cx) / np.linalg.norm(Cx)
                pose_x = ref.fk_123(*left_chain_equilibrium(q0, lf * WRENCH))
                dP = np.array(st["nodes"]["P"]["displacement"])
                e_pos = np.linalg.norm(np.array([dP[5], dP[0], dP[1]]) - (pose_x - np.array([0.0, 0.0, y])))
                worst_loaded = max(worst_loaded, e)
                loaded_rows.append((lf, Cb, e, e_pos, st["stable"]))
    md += ["", "## Loaded path at P1: loaded compliance vs the derivative of the exact equilibrium\n",
           "| load factor | compliance (beamfea) | rel. error | pose error | stable |", "|---|---|---|---|---|"]
    for lf, Cb, e, ep, s in loaded_rows:
        md.append(f"| {lf:.2f} | {fmt_mat(Cb)} | {e:.1e} | {ep:.1e} | {s} |")
    text = "\n".join(md) + "\n"
    with open(os.path.join(OUT, "lumped_tables.md"), "w") as f:
        f.write(text)
    print(text)
    print(f"worst: unloaded {worst_unloaded:.1e} (tolerance {TOL_UNLOADED}), loaded {worst_loaded:.1e} (tolerance {TOL_LOADED})")
    if worst_unloaded > TOL_UNLOADED or worst_loaded > TOL_LOADED:
        sys.exit(1)


if __name__ == "__main__":
    main()
