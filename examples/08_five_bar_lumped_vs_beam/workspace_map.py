#!/usr/bin/python3
"""The five-bar's generated lumped model against its beam model over the workspace: an error map.

    /usr/bin/python3 examples/08_five_bar_lumped_vs_beam/workspace_map.py [--beamfea PATH] [--out DIR] [--quick] [--no-plots]

1. `beamfea.lump` condenses each rod of models/beam.json (links.json) into a 6-D virtual spring:
   models/generated_lumped.json (the same as `beamfea lump models/beam.json --links links.json -o ...`).
2. workspace_spec.json: both models driven by the end point E (`pose.nodes`) over a grid of
   positions x = -0.05 .. 0.25 m, y = 0.25 .. 0.45 m (13 x 9; --quick: 3 x 3 around the reference),
   the tool force 300 N downward at E.
3. scripts/compare_models.py on that spec (scripts/compare_workspace.py): per pose the relative
   differences of the unloaded and loaded compliance of E and of the critical load factor:
   OUT/workspace.csv, OUT/workspace.json, OUT/workspace.png (copied to workspace_error_map.png
   unless --quick).

Exit 1 when the unloaded compliances differ by more than 1e-9 at a pose both models take (each rod
meets the rest only at its two ends, so its condensed spring is exact in the linear range).
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from find_beamfea import import_beamfea  # noqa: E402

E_REF = [0.10000000000000003, 0.3687254596450502, 0.0]  # E at the reference geometry (make_models.py)
FORCE = 300.0                # N, downward at E: below the smallest critical load over the grid
TOL_LINEAR = 1e-9            # unloaded compliance, generated lumped vs beam (relative)


def spec(quick):
    xs = [0.0, 0.1, 0.2] if quick else [round(-0.05 + 0.025 * i, 3) for i in range(13)]
    ys = [0.3, 0.35, 0.4] if quick else [round(0.25 + 0.025 * i, 3) for i in range(9)]
    return {"title": "Five-bar, end point E over the workspace",
            "workspace": {
                "models": [{"key": "lumped", "file": "models/generated_lumped.json", "label": "generated lumped (VJM)"},
                           {"key": "beam", "file": "models/beam.json", "label": "beam model"}],
                "reference": "beam",
                "node": "E",
                "directions": [[1, 0, 0], [0, 1, 0]],
                "set": {"/loads/0/force/1": -FORCE},
                "pose": {"nodes": [{"node": "E", "xyz": E_REF}]},
                "grid": [{"name": "x", "pointer": "/pose/nodes/0/xyz/0", "values": xs},
                         {"name": "y", "pointer": "/pose/nodes/0/xyz/1", "values": ys}]}}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--beamfea", default=None, help="run this beamfea program (default: the Python module)")
    ap.add_argument("--out", default=os.path.join(HERE, "out", "workspace"))
    ap.add_argument("--quick", action="store_true", help="3 x 3 poses, nothing written beside the script")
    ap.add_argument("--no-plots", action="store_true")
    args = ap.parse_args()
    bf = import_beamfea()
    folder = args.out if args.quick else HERE
    os.makedirs(os.path.join(folder, "models"), exist_ok=True)
    bf.lump(os.path.join(HERE, "models", "beam.json"), os.path.join(HERE, "links.json"),
            out=os.path.join(folder, "models", "generated_lumped.json"))
    if args.quick:
        shutil.copy(os.path.join(HERE, "models", "beam.json"), os.path.join(folder, "models", "beam.json"))
    spec_file = os.path.join(folder, "workspace_spec.json")
    with open(spec_file, "w") as f:
        json.dump(spec(args.quick), f, indent=1)
    cmd = [sys.executable, os.path.join(ROOT, "scripts", "compare_models.py"), spec_file, "--out", args.out]
    if args.beamfea:
        cmd += ["--beamfea", args.beamfea]
    if args.no_plots:
        cmd += ["--no-plots"]
    if subprocess.run(cmd).returncode:
        sys.exit("compare_models.py failed")
    with open(os.path.join(args.out, "workspace.csv")) as f:
        rows = list(csv.DictReader(f))
    ok = [r for r in rows if r["status_lumped"] == "ok" and r["status_beam"] == "ok"]
    worst = max(float(r["dC0_t_lumped"]) for r in ok)
    # the loaded compliance below both critical loads (beyond one the loaded stiffness is indefinite)
    loaded = max(float(r["dCL_t_lumped"]) for r in ok if min(float(r["lambda_lumped"]), float(r["lambda_beam"])) > 1.0)
    lam = [float(r["dlambda_lumped"]) for r in ok if r["dlambda_lumped"]]
    print(f"{len(ok)} of {len(rows)} poses in both models; unloaded compliance differs by at most {worst:.1e}, "
          f"loaded ({FORCE:g} N, below the critical load) by at most {100 * loaded:.1f} %, critical load factor by "
          f"{100 * min(lam):+.1f} .. {100 * max(lam):+.1f} %")
    if not args.quick and os.path.exists(os.path.join(args.out, "workspace.png")):
        shutil.copy(os.path.join(args.out, "workspace.png"), os.path.join(HERE, "workspace_error_map.png"))
    if not ok or not worst <= TOL_LINEAR or not math.isfinite(loaded):
        sys.exit(f"check failed: unloaded compliance difference {worst:.2e} > {TOL_LINEAR:g}")


if __name__ == "__main__":
    main()
