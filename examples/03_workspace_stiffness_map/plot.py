#!/usr/bin/python3
"""Heat map of the tip stiffness from out/cases.csv, and a check against the joint springs.

K (6x6, ux uy uz rx ry rz) is the stiffness of the tip node with its rotations kept, so the
stiffness against a force alone (the tip free to rotate) is the inverse of the translational
block of the compliance K^-1. Plots, over (theta1, theta2), log10 of its component k_yy (a
vertical force at the tip) and of the smallest eigenvalue of its in-plane part: the stiffness
in the weakest direction, which depends on theta2 only (a shoulder rotation rotates it). With rigid links the tip compliance would be C = J diag(1/k1, 1/k2) J^T (J the
planar Jacobian); flexible links only add compliance, so the computed stiffness must stay
at or below the rigid-link value, and close to it where the joints dominate.
"""
import csv
import math

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

L1, L2, k1, k2 = 0.4, 0.3, 2000.0, 1000.0

rows = list(csv.DictReader(open("out/cases.csv")))
t1s = sorted({float(r["theta1_deg"]) for r in rows})
t2s = sorted({float(r["theta2_deg"]) for r in rows})
kmin = np.full((len(t1s), len(t2s)), np.nan)
kyy = np.full((len(t1s), len(t2s)), np.nan)
worst_ratio = 0.0
for r in rows:
    if r["status"] != "ok":
        continue
    i, j = t1s.index(float(r["theta1_deg"])), t2s.index(float(r["theta2_deg"]))
    K = np.array([[float(r[f"K[{a}][{b}]"]) for b in range(6)] for a in range(6)])
    K2 = np.linalg.inv(np.linalg.inv(K)[:2, :2])
    kmin[i, j] = np.linalg.eigvalsh(K2)[0]
    kyy[i, j] = K2[1, 1]
    a, b = math.radians(float(r["theta1_deg"])), math.radians(float(r["theta1_deg"]) + float(r["theta2_deg"]))
    J = np.array([[-L1 * math.sin(a) - L2 * math.sin(b), -L2 * math.sin(b)],
                  [L1 * math.cos(a) + L2 * math.cos(b), L2 * math.cos(b)]])
    C_rigid = J @ np.diag([1 / k1, 1 / k2]) @ J.T
    if abs(np.linalg.det(J)) > 1e-3:
        K_rigid = np.linalg.inv(C_rigid)
        worst_ratio = max(worst_ratio, kmin[i, j] / np.linalg.eigvalsh(K_rigid)[0])

ok = sum(r["status"] == "ok" for r in rows)
print(f"{ok}/{len(rows)} cases ok; weakest-direction stiffness {np.nanmin(kmin):.4g} .. {np.nanmax(kmin):.4g} N/m")
print(f"largest ratio to the rigid-link joint-spring value (away from theta2 = 0): {worst_ratio:.4f} (must be <= 1)")

fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), sharey=True)
for ax, field, title in ((axes[0], kyy, "log10 k_yy [N/m]"), (axes[1], kmin, "log10 weakest-direction stiffness [N/m]")):
    im = ax.pcolormesh(t2s, t1s, np.log10(field), shading="nearest", cmap="viridis")
    ax.set_xlabel("elbow angle theta2 [deg]")
    ax.set_title(title)
    fig.colorbar(im, ax=ax)
axes[0].set_ylabel("shoulder angle theta1 [deg]")
fig.tight_layout()
fig.savefig("stiffness_map.png", dpi=80)
print("wrote stiffness_map.png")
