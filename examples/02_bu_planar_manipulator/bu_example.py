#!/usr/bin/python3
"""Bu (2012) planar 3-DOF manipulator: every actuator allocation scheme, with beamfea.

    /usr/bin/python3 examples/02_bu_planar_manipulator/bu_example.py [--beamfea PATH] [--no-plots]

1. inverse kinematics at P1..P5 (P = (0, y), y = 1.1 .. 1.5, platform horizontal), branch with
   both elbows outward (the one that reproduces the paper's printed Jacobians);
2. builds the model as a dict: the 6R loop J1..J6 as beams and revolute joints, poses as node
   overrides, "actuator_allocation" analyses (the paper's two schemes, all 20 schemes), and
   writes it to out/bu_model.json for inspection;
3. runs it in process, `beamfea.run(model)` (the Python module), or with --beamfea PATH the
   program, `PATH run out/bu_model.json --out out` (the same engine, the same numbers);
4. writes out/tables.json, out/tables.md and PNG plots of the stiffness along P1..P5.

Units: E is chosen so that EI_z = 1 and k_act = 1, so K_A is in units of k_act and K_S in units
of EI_z (lambda = k_act / EI_z = 1 1/m for the totals), as in docs/notes/bu-reference.md.
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "out")
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from find_beamfea import import_beamfea  # noqa: E402

L12, L23, L3P, L4P, L45, L56 = 0.9, 1.0, 0.4, 0.4, 1.0, 0.6
J1, J6 = np.array([-0.5, 0.0]), np.array([0.5, 0.0])
POSES = {"P1": 1.1, "P2": 1.2, "P3": 1.3, "P4": 1.4, "P5": 1.5}
R_SEC, NU = 0.02, 0.3
I_SEC = math.pi * R_SEC**4 / 4
E_MOD = 1.0 / I_SEC  # EI_z = 1
PAYLOAD = 0.1  # a force on P along -y, in units of k_act / m (the "payload" load case)


def circle_intersections(c1, r1, c2, r2):
    d = np.linalg.norm(c2 - c1)
    a = (r1**2 - r2**2 + d**2) / (2 * d)
    h = math.sqrt(r1**2 - a**2)
    m = c1 + a * (c2 - c1) / d
    n = np.array([-(c2 - c1)[1], (c2 - c1)[0]]) / d
    return m + h * n, m - h * n


def inverse_kinematics(y):
    P = np.array([0.0, y])
    J3, J4 = P + [-L3P, 0.0], P + [L4P, 0.0]
    J2 = min(circle_intersections(J1, L12, J3, L23), key=lambda p: p[0])  # elbow out (left)
    J5 = max(circle_intersections(J6, L56, J4, L45), key=lambda p: p[0])  # elbow out (right)
    return {"J1": J1, "J2": J2, "J3": J3, "P": P, "J4": J4, "J5": J5, "J6": J6}


def xyz(p):
    return [float(p[0]), float(p[1]), 0.0]


def model(poses):
    ref = poses["P1"]
    nodes = []
    for j in ["J1", "J2", "J3", "J4", "J5", "J6"]:
        nodes += [{"id": j + "a", "xyz": xyz(ref[j])}, {"id": j + "b", "xyz": xyz(ref[j])}]
    nodes.append({"id": "P", "xyz": xyz(ref["P"])})

    def beam(i, a, b):
        return {"id": i, "type": "beam", "nodes": [a, b], "material": "steel", "section": "rod"}

    # Link naming follows the paper's tables; each link is one element (exact for end loads).
    elements = [beam("J1J2", "J1b", "J2a"), beam("J2J3", "J2b", "J3a"), beam("J3P", "J3b", "P"),
                beam("J4P", "J4a", "P"), beam("J4J5", "J4b", "J5a"), beam("J5J6", "J5b", "J6a")]
    # A revolute coordinate is the rotation of the body of nodes[1] relative to that of nodes[0].
    # The paper measures every limb from the base outwards (eqs. 21-22): the left limb J1 -> J3,
    # the right limb J6 -> J4, so the right joints list their base-side node first.
    joints = [{"id": j, "type": "revolute", "nodes": [j + "a", j + "b"], "axes": [[0, 0, 1]]}
              for j in ["J1", "J2", "J3"]]
    joints += [{"id": j, "type": "revolute", "nodes": [j + "b", j + "a"], "axes": [[0, 0, 1]]}
               for j in ["J4", "J5", "J6"]]
    pose_list = []
    for name, pos in poses.items():
        pose_list.append({"id": name, "nodes": [{"node": j + "a", "xyz": xyz(pos[j])}
                                                 for j in ["J2", "J3", "J4", "J5"]] +
                          [{"node": "P", "xyz": xyz(pos["P"])}]})
    common = {
        "type": "actuator_allocation",
        "platform_node": "P",
        "candidate_joints": ["J1", "J2", "J3", "J4", "J5", "J6"],
        "actuators": 3,
        "actuator_stiffness": 1.0,
        "directions": ["rz", "ux", "uy"],
        "structural_terms": ["bending"],
        "poses": pose_list,
        "rank_by": {"stiffness": "total", "direction": "uy"},
    }
    return {
        "title": "Bu (2012) planar 3-DOF parallel manipulator, Fig. 8 / Table 2",
        "nodes": nodes,
        "materials": [{"id": "steel", "E": E_MOD, "nu": NU}],
        "sections": [{"id": "rod", "shape": "circle", "r": R_SEC}],
        "elements": elements,
        "joints": joints,
        # Ground: J1a and J6b; J6 joins link J5J6 (J6a) to the ground (J6b).
        "supports": [{"node": "J1a", "fix": "all"}, {"node": "J6b", "fix": "all"}],
        # A payload on the platform (the machine works in a vertical plane, y up).
        "load_cases": [{"id": "payload", "loads": [{"node": "P", "force": [0.0, -PAYLOAD, 0.0]}]}],
        "analyses": [
            dict(common, id="paper", schemes=[["J1", "J2", "J3"], ["J1", "J2", "J6"]]),
            dict(common, id="all"),
            dict(common, id="all_terms", structural_terms=["axial", "shear", "torsion", "bending"],
                 schemes=[["J1", "J2", "J3"], ["J1", "J2", "J6"]]),
            # What the payload does to each scheme: motor torques, sag, loaded stiffness (K + K_g).
            dict(common, id="payload", schemes=[["J1", "J2", "J3"], ["J1", "J2", "J6"]], load_case="payload"),
        ],
    }


def fmt_mat(m):
    return "[" + "; ".join(" ".join(f"{v:+.4f}" for v in row) for row in m) + "]"


def main():
    global OUT
    ap = argparse.ArgumentParser()
    ap.add_argument("--beamfea", default=None,
                    help="run this beamfea program instead of the Python module (the same engine)")
    ap.add_argument("--no-plots", action="store_true")
    ap.add_argument("--out", default=OUT, help="output folder (default: out/ beside this script)")
    args = ap.parse_args()
    OUT = os.path.abspath(args.out)
    os.makedirs(OUT, exist_ok=True)
    poses = {k: inverse_kinematics(y) for k, y in POSES.items()}
    doc = model(poses)
    path = os.path.join(OUT, "bu_model.json")
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
    if args.beamfea:
        subprocess.run([args.beamfea, "run", path, "--out", OUT, "--no-vtk", "--quiet"], check=True)
        with open(os.path.join(OUT, "results.json")) as f:
            res = json.load(f)["analyses"]
    else:
        # arrays come back as NumPy arrays; out= also writes results.json and the CSV tables
        res = import_beamfea().run(doc, out=OUT, vtk=False)["analyses"]

    # Tables: per scheme and pose, J, K_A, per-link integrals (unit y-force), K_S, totals.
    tables = {"paper": {}, "all": []}
    md = ["## Paper's schemes (units: k_act for K_A, EI_z for K_S, lambda = k_act/EI_z = 1/m)\n"]
    for s in res["paper"]["schemes"]:
        md.append(f"### Scheme {s['scheme']}\n")
        md.append("| pose | J | K_A (Jacobian, eq. 10) | K_A jac vs condensed |")
        md.append("|---|---|---|---|")
        for p in s["poses"]:
            a = p["actuated"]
            md.append(f"| {p['pose']} | {fmt_mat(a['J'])} | {fmt_mat(a['K_jacobian'])} | {a['jacobian_vs_condensed']:.1e} |")
        md.append("")
        md.append("| pose | " + " | ".join(l["member"] for l in s["poses"][0]["structural"]["links"]) +
                  " | total | K_S,y (EI_z) | K_A,yy | K total eq. 19 | K total consistent | VF vs FEA |")
        md.append("|---|" + "---|" * (len(s["poses"][0]["structural"]["links"]) + 6))
        rows = []
        for p in s["poses"]:
            links = p["structural"]["links"]
            ints = [l["integrals"]["uy"]["Mz2"] for l in links]
            c = p["components"]
            rows.append({"pose": p["pose"], "J": p["actuated"]["J"], "K_A": p["actuated"]["K_jacobian"],
                         "int_Mz2": dict(zip([l["member"] for l in links], ints)),
                         "K_S_y": c["structural"]["uy"], "K_A_yy": c["actuated"]["uy"],
                         "total_eq19_y": c["total_eq19"]["uy"], "total_y": c["total"]["uy"],
                         "components": c})
            md.append(f"| {p['pose']} | " + " | ".join(f"{v:.4f}" for v in ints) +
                      f" | {sum(ints):.4f} | {c['structural']['uy']:.4f} | {c['actuated']['uy']:.4f} | "
                      f"{c['total_eq19']['uy']:.4f} | {c['total']['uy']:.4f} | "
                      f"{p['structural']['virtual_force_vs_fea']:.1e} |")
        md.append("")
        tables["paper"][s["scheme"]] = rows
    md.append("## All 20 schemes, ranked by the consistent total stiffness in y, worst pose\n")
    md.append("| rank | scheme | worst K_y | at | K_A,yy P1 | K_S,y P1 |")
    md.append("|---|---|---|---|---|---|")
    by_name = {s["scheme"]: s for s in res["all"]["schemes"]}
    for r in res["all"]["ranking"]:
        s = by_name[r["scheme"]]
        c1 = s["poses"][0]["components"]
        wv = f"{r['worst_value']:.4f}" if r["worst_value"] is not None else r["status"]
        md.append(f"| {r['rank'] if r['rank'] is not None else '-'} | {r['scheme']} | {wv} | {r['worst_pose']} | "
                  f"{c1['actuated']['uy'] or float('nan'):.4f} | {c1['structural']['uy'] or float('nan'):.4f} |")
        tables["all"].append({"rank": r["rank"], "scheme": r["scheme"], "worst_total_y": r["worst_value"],
                              "worst_pose": r["worst_pose"],
                              "poses": {p["pose"]: p["components"] for p in s["poses"]}})
    md.append(f"\n## Payload {PAYLOAD} k_act/m on P along -y (load_case \"payload\")\n")
    md.append("| scheme | pose | motor torques (k_act rad) | max abs(tau + J^T W) | uy total | uy actuated | "
              "K_y total unloaded | K_y total loaded |")
    md.append("|---|---|---|---|---|---|---|---|")
    tables["payload"] = {}
    for s in res["payload"]["schemes"]:
        rows = []
        for p in s["poses"]:
            tau = np.array([e["effort"] for e in p["actuator_efforts"]])
            J = np.array(p["actuated"]["J"])
            W = np.array([0.0, 0.0, -PAYLOAD])  # [Mz, Fx, Fy] in the order of "directions"
            check = float(np.abs(tau + J.T @ W).max())
            # The frozen structures are statically determinate in the plane: statics of J exactly.
            if not check < 1e-9 * PAYLOAD:
                raise SystemExit(f"motor torques of {s['scheme']} at {p['pose']} differ from -J^T W by {check:.2e}")
            d = p["platform_displacement"]
            k0, k1 = p["components"]["total"]["uy"], p["loaded_stiffness"]["components"]["total"]["uy"]
            md.append(f"| {s['scheme']} | {p['pose']} | " + " ".join(f"{t:+.4f}" for t in tau) +
                      f" | {check:.1e} | {d['total']['uy']:+.4f} | {d['actuated']['uy']:+.4f} | {k0:.4f} | {k1:.4f} |")
            rows.append({"pose": p["pose"], "efforts": tau.tolist(), "jacobian_check": check,
                         "uy_total": d["total"]["uy"], "uy_actuated": d["actuated"]["uy"],
                         "K_y_total": k0, "K_y_total_loaded": k1})
        tables["payload"][s["scheme"]] = rows
    with open(os.path.join(OUT, "tables.json"), "w") as f:
        json.dump(tables, f, indent=1, default=lambda a: a.tolist())  # NumPy arrays as lists
    with open(os.path.join(OUT, "tables.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))
    if not args.no_plots:
        plots(res)


def plots(res):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = list(POSES)
    x = [POSES[n] for n in names]
    # Fig. 10 analogue: actuated stiffness k_omega, k_x, k_y along P1..P5, both schemes.
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    styles = {"J1+J2+J3": "-", "J1+J2+J6": "--"}
    colors = {"rz": "b", "ux": "g", "uy": "r"}
    for s in res["paper"]["schemes"]:
        for d in ["rz", "ux", "uy"]:
            ax[0].plot(x, [p["components"]["actuated"][d] for p in s["poses"]], styles[s["scheme"]] + "o",
                       color=colors[d], label=f"{s['scheme']} K_A,{d}")
        ax[1].plot(x, [p["components"]["structural"]["uy"] for p in s["poses"]], styles[s["scheme"]] + "o",
                   color="k", label=f"{s['scheme']} K_S,y")
        ax[1].plot(x, [p["components"]["total"]["uy"] for p in s["poses"]], styles[s["scheme"]] + "s",
                   color="m", label=f"{s['scheme']} K_y total")
    ax[0].set(xlabel="y of P (m)", ylabel="K_A diagonal (k_act, k_act/m^2)", title="actuated stiffness (Fig. 10)")
    ax[1].set(xlabel="y of P (m)", ylabel="EI_z/m^3", yscale="log", title="structural and total, y (Fig. 11)")
    for a in ax:
        a.legend(fontsize=7)
        a.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "paper_schemes.png"), dpi=90)
    # All 20: consistent total y stiffness along P1..P5.
    fig, ax = plt.subplots(figsize=(8, 5))
    for s in res["all"]["schemes"]:
        v = [p["components"]["total"]["uy"] for p in s["poses"]]
        if any(t is None for t in v):
            continue
        ax.plot(x, v, "o-", label=s["scheme"], lw=1)
    ax.set(xlabel="y of P (m)", ylabel="K_y total (EI_z/m^3, lambda = 1/m)", yscale="log",
           title="all 20 allocation schemes")
    ax.legend(fontsize=6, ncol=2)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "all_schemes.png"), dpi=90)


if __name__ == "__main__":
    main()
