#!/usr/bin/python3
"""Force-displacement curves of the portal frame from out/cases.csv, checked in closed form.

With a rigid girder the column tops translate without rotating, so each clamped column is a
fixed-guided beam of sway stiffness 12 E I / h^3 (Przemieniecki, Theory of Matrix Structural
Analysis, eq. 5.116) and the frame's is k = 24 E I / h^3, I = b^4 / 12 for a square column.
The base moment of each column is M = (H / 2) h / 2.
"""
import csv

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

E, h = 210e9, 3.0
rows = [r for r in csv.DictReader(open("out/cases.csv")) if r["status"] == "ok"]
fig, ax = plt.subplots(figsize=(6, 4))
worst = 0.0
for b in sorted({float(r["column_b"]) for r in rows}):
    rs = sorted((r for r in rows if float(r["column_b"]) == b), key=lambda r: float(r["H"]))
    H = [float(r["H"]) / 1e3 for r in rs]
    u = [float(r["sway"]) * 1e3 for r in rs]
    k = 24 * E * (b ** 4 / 12) / h ** 3
    for r in rs:
        Hr = float(r["H"])
        worst = max(worst, abs(float(r["sway"]) - Hr / k) / (50e3 / k))
        worst = max(worst, abs(abs(float(r["base_moment_A"])) - Hr / 2 * h / 2) / (50e3 / 2 * h / 2))
    ax.plot(u, H, "o-", label=f"column {b * 1e3:.0f} x {b * 1e3:.0f} mm (k = {k / 1e6:.2f} kN/mm)")
ax.set_xlabel("sway of the girder [mm]")
ax.set_ylabel("lateral load H [kN]")
ax.set_title("Portal frame: load sweep, 3 column sizes x 11 load levels")
ax.grid(True, alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig("force_displacement.png", dpi=80)
print(f"{len(rows)} cases ok; largest relative deviation from 24EI/h^3 and Hh/4: {worst:.2e}")
print("wrote force_displacement.png")
