#!/usr/bin/python3
"""The comparison report of the Pashkevich chain: one command regenerates everything.

  /usr/bin/python3 examples/05_pashkevich_chain/report.py \\
      --out examples/05_pashkevich_chain/out [--skip-convergence] [--beamfea build/cli/beamfea]

Every model runs in process with the Python module (beamfea.run, docs/python.md); with
--beamfea PATH the program runs them instead (the same engine, the same numbers).

1. writes the models (generate.py: models A, B, C x postures S, Pi, Z, lumped and beam, and the
   mesh / spring-count series under OUT/conv_models/);
2. runs the general driver scripts/compare_models.py on comparison_spec.json: OUT/summary.md
   (lumped vs beam vs paper vs verified reference), OUT/<pair>.png, OUT/<pair>/<model>.csv,
   OUT/<pair>/<model>/path.pvd (ParaView series of the posture's evolution);
3. the convergence study: critical force (S posture: the "buckling" analysis of the straight
   chain; Pi, Z: the first critical point of the path) of the beam model for N = 1, 2, 4, 8, 16
   elements per link and of the lumped model for n = 1, 2, 4, 8, 16 springs per link:
   OUT/convergence.md and OUT/convergence.csv.
"""
import argparse
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import compare_models as cm  # noqa: E402

NS = (1, 2, 4, 8, 16)
DELTA_CONV = 0.3


def critical_force(exe, file, out_dir, log):
    doc = cm.load(file)
    res, missing, err = cm.run_beamfea(exe, doc, out_dir, log)
    if not res:
        return None, f"error: {err}"
    an = res.get("analyses", {})
    if "buckling" in an and cm.nonempty(an["buckling"].get("load_factors")):
        return an["buckling"]["load_factors"][0], "buckling"
    p = an.get("path")
    if p is None:
        return None, "missing: " + ", ".join(missing)
    if p.get("critical_points"):
        return p["critical_points"][0]["load_factor"], p["critical_points"][0].get("type", "critical")
    if not p.get("completed", False):
        return None, "path failed"
    # no critical point: the force at the end of the path (delta = DELTA_CONV) instead
    P = cm.interp(DELTA_CONV, [-s["nodes"]["E"]["displacement"][0] for s in p["steps"]],
                  [s["load_factor"] for s in p["steps"]])
    return P, f"P at delta = {DELTA_CONV} L (no critical point)"


def convergence(exe, out, log, postures=("S", "Pi", "Z")):
    rows = []
    for model in "BC":
        for posture in postures:
            for kind, letter in (("beam", "N"), ("lumped", "n")):
                vals = []
                for n in NS:
                    f = os.path.join(out, "conv_models", f"{model}_{posture}_{kind}_{letter}{n}.json")
                    doc = cm.load(f)
                    if posture == "S":  # the straight chain: buckling analysis only (the path is in the report)
                        doc["analyses"] = [a for a in doc["analyses"] if a["type"] == "buckling"]
                    else:  # the critical points lie below delta = 0.15 L: stop at 0.3 L, record P there too
                        doc["analyses"][0]["stop"]["beyond"] = -DELTA_CONV
                    tmp = os.path.join(out, "conv", f"{model}_{posture}_{kind}_{letter}{n}")
                    os.makedirs(tmp, exist_ok=True)
                    with open(os.path.join(tmp, "in.json"), "w") as fh:
                        json.dump(doc, fh)
                    v, how = critical_force(exe, os.path.join(tmp, "in.json"), tmp, log)
                    log(f"  {model} {posture} {kind} {letter}={n}: {v} ({how})")
                    vals.append((v, how))
                rows.append((model, posture, kind, vals))
    with open(os.path.join(out, "convergence.csv"), "w") as f:
        f.write("model,posture,kind," + ",".join(f"n{n}" for n in NS) + "\n")
        for model, posture, kind, vals in rows:
            f.write(f"{model},{posture},{kind}," + ",".join("" if v is None else f"{v:.8g}" for v, _ in vals) + "\n")
    with open(os.path.join(out, "convergence.md"), "w") as f:
        f.write("Critical force [K_theta/L] against N elements per link (beam) or n springs per link (lumped).\n"
                "Relative change = |F(16) - F(8)| / F(16).\n\n")
        f.write("| model | posture | model kind | " + " | ".join(str(n) for n in NS) + " | rel. change 8->16 |\n")
        f.write("|---|---|---|" + "---|" * (len(NS) + 1) + "\n")
        for model, posture, kind, vals in rows:
            cells = [(cm.fmt(v) + ("*" if how.startswith("P at") else "")) if v is not None else how for v, how in vals]
            a, b = vals[-2][0], vals[-1][0]
            rel = f"{abs(b - a) / abs(b):.1e}" if a is not None and b is not None and b != 0 else "—"
            f.write(f"| {model} | {posture} | {kind} | " + " | ".join(cells) + f" | {rel} |\n")
        f.write(f"\n\\* no critical point (model B, Pi; model B, Z lumped: an imperfect bifurcation): the force P at "
                f"delta = {DELTA_CONV} L instead.\nS posture: the buckling analysis of the straight chain; Pi, Z: the "
                "first critical point of the path (bisection to 1e-3 of the step).\n")
        f.write(f"\nEuler load of the pinned-pinned column of length 3L: pi^2/9 = {math.pi ** 2 / 9:.6f} (B, in plane), "
                f"0.16 pi^2/9 = {0.16 * math.pi ** 2 / 9:.6f} (C, out of plane).\n")


def figures(out, log):
    """Two figures from the convergence runs: S-posture critical force against the number of
    elements / springs per link, and the first buckling mode of the straight chain, lumped vs beam."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    conv = os.path.join(out, "conv")

    def lf(name):
        f = os.path.join(conv, name, "results.json")
        if not os.path.exists(f):
            return None
        a = cm.load(f)["analyses"].get("buckling")
        return a if a and cm.nonempty(a.get("load_factors")) else None

    fig, ax = plt.subplots(figsize=(6, 4))
    for model, scale, col in (("B", 1.0, "C0"), ("C", 0.16, "C3")):
        PE = scale * math.pi ** 2 / 9
        for kind, letter, mk in (("beam", "N", "o-"), ("lumped", "n", "s--")):
            pts = [(n, lf(f"{model}_S_{kind}_{letter}{n}")) for n in NS]
            pts = [(n, abs(a["load_factors"][0] - PE) / PE) for n, a in pts if a]
            if pts:
                ax.loglog(*zip(*pts), mk, color=col, label=f"model {model}, {kind} ({letter} per link)")
    ax.set_xlabel("elements (beam) or virtual springs (lumped) per link")
    ax.set_ylabel("|F_cr - Euler| / Euler, S posture")
    ax.set_title("Straight chain: convergence to the Euler load of a 3L column", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    os.makedirs(os.path.join(out, "figures"), exist_ok=True)
    fig.savefig(os.path.join(out, "figures", "convergence_S.png"), dpi=80)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 3.6))
    xs = [i / 100 * 3 for i in range(101)]
    ax.plot(xs, [math.sin(math.pi * x / 3) for x in xs], "k:", label="Euler half-sine")
    for name, label, st in (("B_S_lumped_n1", "lumped, 1 spring/link", "s-"), ("B_S_lumped_n2", "lumped, 2 springs/link", "^-"),
                            ("B_S_beam_N8", "beam, 8 elements/link", "o-")):
        a = lf(name)
        if not a:
            continue
        nodes = cm.load(os.path.join(out, "conv_models", name.replace("B_S_", "B_S_") + ".json"))["nodes"]
        mode = a["modes"][0]["nodes"]
        pts = sorted((n["xyz"][0], mode[n["id"]]["displacement"][1]) for n in nodes if n["id"] in mode)
        # meshed beam nodes are not in the model file: take all mode nodes with their x
        if "beam" in name:
            ids = list(mode.keys())
            xyz = {n["id"]: n["xyz"][0] for n in nodes}
            pts = []
            for i in ids:
                if i in xyz:
                    pts.append((xyz[i], mode[i]["displacement"][1]))
                elif "#" in i:
                    link, k = i.split("#")
                    li = int(link.replace("link", ""))
                    pts.append((li - 1 + int(k) / 8.0, mode[i]["displacement"][1]))
            pts.sort()
        m = max(abs(p[1]) for p in pts) or 1.0
        sgn = 1.0 if sum(p[1] for p in pts) >= 0 else -1.0
        ax.plot([p[0] for p in pts], [sgn * p[1] / m for p in pts], st, ms=3,
                label=f"{label}: F_cr = {a['load_factors'][0]:.4f}")
    ax.set_xlabel("x [L]")
    ax.set_ylabel("first buckling mode, y (normalised)")
    ax.set_title("Model B, S posture: lumped chain kinks at its springs, beams bend", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower center")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "figures", "buckling_mode_S.png"), dpi=80)
    plt.close(fig)
    log(f"figures in {out}/figures")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--beamfea", default=None, help="run this beamfea program (default: the Python module, in process)")
    ap.add_argument("--out", default=os.path.join(HERE, "out"))
    ap.add_argument("--skip-convergence", action="store_true")
    ap.add_argument("--only", nargs="*", default=None)
    ap.add_argument("--convergence-postures", nargs="*", default=["S", "Pi", "Z"],
                    help="postures of the convergence study (S uses the buckling analysis, Pi and Z the path)")
    ap.add_argument("--reuse", action="store_true", help="reuse the results of unchanged models in OUT")
    args = ap.parse_args()
    cm.REUSE = args.reuse
    exe = os.path.abspath(args.beamfea) if args.beamfea else None
    log = lambda s: print(s, file=sys.stderr, flush=True)
    subprocess.run([sys.executable, os.path.join(HERE, "generate.py"), "--convergence",
                    os.path.join(args.out, "conv_models")], check=True)
    cmd = [sys.executable, os.path.join(ROOT, "scripts", "compare_models.py"), os.path.join(HERE, "comparison_spec.json"),
           "--out", args.out] + (["--beamfea", exe] if exe else [])
    if args.only:
        cmd += ["--only"] + args.only
    if args.reuse:
        cmd += ["--reuse"]
    subprocess.run(cmd, check=True)
    if not args.skip_convergence:
        log("convergence study")
        convergence(exe, args.out, log, args.convergence_postures)
        figures(args.out, log)
    log(f"report in {args.out}")


if __name__ == "__main__":
    main()
