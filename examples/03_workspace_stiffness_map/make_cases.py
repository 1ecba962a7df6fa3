#!/usr/bin/python3
"""Writes sweep.json: one case per pose (theta1, theta2) of the two-link chain in model.json.

Joint coordinates in beamfea are small-displacement DOFs, so a pose is geometry: each case
sets the elbow nodes E1, E2 and the tip T to the forward kinematics of the two angles
    E = L1 (cos t1, sin t1),   T = E + L2 (cos(t1 + t2), sin(t1 + t2)).
The angles go into the table as the case's parameters. plot.py imports sweep_spec() to run the
same sweep in process.
"""
import json
import math

L1, L2 = 0.4, 0.3
THETA1 = [5.0 * i for i in range(0, 19)]          # 0 .. 90 degrees
THETA2 = [5.0 * i for i in range(-30, 31)]        # -150 .. 150 degrees


def sweep_spec(base="model.json", step=1):
    """The sweep document; `step` > 1 takes every step-th angle of each list (a quick run)."""
    cases = []
    for t1 in THETA1[::step]:
        for t2 in THETA2[::step]:
            a, b = math.radians(t1), math.radians(t1 + t2)
            e = [L1 * math.cos(a), L1 * math.sin(a), 0.0]
            t = [e[0] + L2 * math.cos(b), e[1] + L2 * math.sin(b), 0.0]
            cases.append({
                "id": f"t1={t1:g}_t2={t2:g}",
                "parameters": {"theta1_deg": t1, "theta2_deg": t2},
                "set": {"/nodes/2/xyz": e, "/nodes/3/xyz": e, "/nodes/4/xyz": t},
            })
    return {
        "description": "End-effector stiffness of a planar two-link chain over its workspace",
        "base": base,
        "cases": cases,
        "outputs": [{"name": "K", "path": "analyses.K.matrix"}],
    }


if __name__ == "__main__":
    sweep = sweep_spec()
    with open("sweep.json", "w") as f:
        json.dump(sweep, f, indent=1)
    print(f"sweep.json: {len(sweep['cases'])} cases")
