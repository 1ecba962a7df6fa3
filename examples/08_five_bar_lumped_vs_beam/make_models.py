#!/usr/bin/python3
"""Planar five-bar parallel manipulator (2 DOF): the lumped model (rigid links, revolute joints,
actuator springs) and the beam model (the same links as steel beams), and the comparison report
through scripts/compare_models.py.

    /usr/bin/python3 examples/08_five_bar_lumped_vs_beam/make_models.py [--beamfea PATH] [--out DIR]

Geometry (m): actuated pivots A1 = (0, 0) and A2 = (G, 0), proximal links L1 at q1, q2 (actuator
springs K_ACT N m/rad), distal links L2 joined at the end point E (passive revolute joints at B1, B2, E),
all axes z. The loop closes at E's joint. Writes models/lumped.json, models/beam.json and
comparison_spec.json (with the closed-form unloaded compliance J K^-1 J^T as the reference column),
then runs the driver: OUT/summary.md, OUT/five_bar.png.
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
G, L1, L2, Q1, Q2 = 0.2, 0.25, 0.25, math.radians(115.0), math.radians(65.0)
K_ACT = 2000.0                     # N m / rad at both actuators
E_STEEL, NU, D_ROD = 2.1e11, 0.3, 0.012   # beam links: solid steel rods of 12 mm
F_REF = 1000.0                     # N, the tool force (downward at E) at load factor 1
LOADED_AT = 0.3                    # load factor of the loaded compliance (300 N, below both limit loads)


def circle_intersection(P1, r1, P2, r2):
    """The intersection of |P - P1| = r1 and |P - P2| = r2 on the left of P1 -> P2."""
    d = P2 - P1
    l = np.linalg.norm(d)
    a = (r1 * r1 - r2 * r2 + l * l) / (2 * l)
    h = math.sqrt(max(0.0, r1 * r1 - a * a))
    e = d / l
    return P1 + a * e + h * np.array([-e[1], e[0]])


def geometry(q1=Q1, q2=Q2):
    A1, A2 = np.array([0.0, 0.0]), np.array([G, 0.0])
    B1 = A1 + L1 * np.array([math.cos(q1), math.sin(q1)])
    B2 = A2 + L1 * np.array([math.cos(q2), math.sin(q2)])
    E = circle_intersection(B1, L2, B2, L2)
    return {"A1": A1, "A2": A2, "B1": B1, "B2": B2, "E": E}


def jacobian(q1=Q1, q2=Q2, h=1e-7):
    """dE/dq by central differences of the closed-form kinematics (2 x 2)."""
    cols = []
    for dq in (np.array([h, 0.0]), np.array([0.0, h])):
        cols.append((geometry(q1 + dq[0], q2 + dq[1])["E"] - geometry(q1 - dq[0], q2 - dq[1])["E"]) / (2 * h))
    return np.column_stack(cols)


def equilibrium(F, q=None):
    """The lumped model's exact equilibrium K_ACT (q - q0) = J(q)^T F (Newton, central-difference
    Hessian); returns q and the smallest eigenvalue of the symmetrised Hessian (stability)."""
    q0 = np.array([Q1, Q2])
    q = q0.copy() if q is None else q.copy()
    res = lambda x: K_ACT * (x - q0) - jacobian(*x).T @ F
    for _ in range(60):
        r = res(q)
        H = np.column_stack([(res(q + e) - res(q - e)) / 2e-6 for e in np.eye(2) * 1e-6])
        if np.abs(r).max() < 1e-9 * K_ACT:
            break
        q = q - np.linalg.solve(H, r)
    return q, np.linalg.eigvalsh(0.5 * (H + H.T))[0]


def closed_form(load_factor):
    """Unloaded compliance J K^-1 J^T (uy, uy), the loaded compliance d u_y / d F_y at the load factor
    (central differences of the exact equilibrium) and the limit load (the first maximum of the load
    along the symmetric primary path), all for the lumped model."""
    J = jacobian()
    c0 = (J @ np.diag([1 / K_ACT, 1 / K_ACT]) @ J.T)[1, 1]
    F = np.array([0.0, -load_factor * F_REF])
    q, _ = equilibrium(F)
    h = 1e-3 * F_REF
    qp, _ = equilibrium(F + [0, h], q)
    qm, _ = equilibrium(F - [0, h], q)
    c1 = (geometry(*qp)["E"][1] - geometry(*qm)["E"][1]) / (2 * h)
    # Limit load: the model and the load are symmetric about x = G/2, so the primary path is
    # q1 = Q1 + t, q2 = Q2 - t with f(t) = K_ACT t / (dE_y/dq2) from the second equilibrium equation;
    # the limit point is the first maximum of f (golden-section search on the first hump).
    f = lambda t: K_ACT * t / jacobian(Q1 + t, Q2 - t)[1, 1]
    t, dt = 0.0, 1e-3
    while f(t + dt) > f(t):
        t += dt
    a_, b_ = max(0.0, t - dt), t + dt
    g = (math.sqrt(5) - 1) / 2
    for _ in range(80):
        c_, d_ = b_ - g * (b_ - a_), a_ + g * (b_ - a_)
        if f(c_) > f(d_):
            b_ = d_
        else:
            a_ = c_
    fcr = f(0.5 * (a_ + b_))
    return c0, c1, fcr


def xyz(p):
    return [float(p[0]), float(p[1]), 0.0]


def model(beams):
    p = geometry()
    nodes = []
    for n in ("A1", "A2", "B1", "B2", "E"):
        nodes += [{"id": n, "xyz": xyz(p[n])}, {"id": n + "p", "xyz": xyz(p[n])}]
    links = [("prox1", "A1p", "B1"), ("dist1", "B1p", "E"), ("prox2", "A2p", "B2"), ("dist2", "B2p", "Ep")]
    if beams:
        elements = [{"id": i, "type": "beam", "nodes": [a, b], "material": "steel", "section": "rod",
                     "orientation": [0, 0, 1], "divisions": 4} for i, a, b in links]
    else:
        elements = [{"id": i, "type": "rigid", "nodes": [a, b]} for i, a, b in links]
    z = [[0, 0, 1]]
    joints = [{"id": "act1", "type": "revolute", "nodes": ["A1", "A1p"], "axes": z, "stiffness": [K_ACT]},
              {"id": "act2", "type": "revolute", "nodes": ["A2", "A2p"], "axes": z, "stiffness": [K_ACT]},
              {"id": "pB1", "type": "revolute", "nodes": ["B1", "B1p"], "axes": z},
              {"id": "pB2", "type": "revolute", "nodes": ["B2", "B2p"], "axes": z},
              {"id": "pE", "type": "revolute", "nodes": ["E", "Ep"], "axes": z}]
    doc = {"_comment": "planar five-bar, " + ("beam links" if beams else "lumped: rigid links"),
           "nodes": nodes, "elements": elements, "joints": joints,
           "supports": [{"node": "A1", "fix": "all"}, {"node": "A2", "fix": "all"}],
           "loads": [{"node": "E", "force": [0.0, -F_REF, 0.0]}],
           "analyses": [{"id": "path", "type": "path", "track": ["E"], "stiffness_node": "E",
                         "control": {"arc_length": 0.01, "max": 0.02},
                         "stop": {"node": "E", "dof": "uy", "beyond": -0.15}, "max_steps": 300}]}
    if beams:
        doc["materials"] = [{"id": "steel", "E": E_STEEL, "nu": NU}]
        doc["sections"] = [{"id": "rod", "shape": "circle", "d": D_ROD}]
    return doc


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--beamfea", default=os.path.join(ROOT, "build", "cli", "beamfea"))
    ap.add_argument("--out", default=os.path.join(HERE, "out"))
    args = ap.parse_args()
    os.makedirs(os.path.join(HERE, "models"), exist_ok=True)
    for name, beams in (("lumped", False), ("beam", True)):
        with open(os.path.join(HERE, "models", name + ".json"), "w") as f:
            json.dump(model(beams), f, indent=1)
    c0, c1, fcr = closed_form(LOADED_AT)
    spec = {"title": "Planar five-bar: lumped (rigid links, actuator springs) vs beam links (steel rods 12 mm)",
            "path_analysis": "path",
            "force": {"from": "load_factor", "scale": F_REF, "label": "F [N], downward at E"},
            "deflection": {"node": "E", "dof": "uy", "scale": -1, "label": "-u_y(E) [m]"},
            "stiffness_node": "E",
            "quantities": ["unloaded_compliance", "loaded_compliance", "critical_force", "P_at_L"],
            "large_deflection": 0.1, "loaded_at": LOADED_AT,
            "pairs": [{"id": "five_bar", "name": "five-bar, tool force downward at E",
                       "models": [{"key": "lumped", "file": "models/lumped.json", "label": "lumped (VJM)"},
                                  {"key": "beam", "file": "models/beam.json", "label": "beam links"}],
                       "values": {"closed form (lumped)": {"unloaded_compliance": float(c0), "loaded_compliance": float(c1),
                                                           "critical_force": float(fcr)}}}]}
    spec_file = os.path.join(HERE, "comparison_spec.json")
    with open(spec_file, "w") as f:
        json.dump(spec, f, indent=1)
    print(f"closed form (lumped): J K^-1 J^T (uy, uy) = {c0:.6g} m/N, loaded at {LOADED_AT} F_REF {c1:.6g} m/N, "
          f"limit load {fcr:.6g} N")
    sys.exit(subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "compare_models.py"), spec_file,
                             "--beamfea", args.beamfea, "--out", args.out]).returncode)


if __name__ == "__main__":
    main()
