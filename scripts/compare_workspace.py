#!/usr/bin/python3
"""Workspace comparison: two (or more) models of the same manipulator, a lumped (VJM) model and its
beam model, compared pose by pose over a list or a grid of poses (docs/analyses/lumped-models.md,
"Comparing over the workspace"). Run through scripts/compare_models.py with a spec that has a
"workspace" key, or directly:

  /usr/bin/python3 scripts/compare_workspace.py SPEC --out OUT [--beamfea build/cli/beamfea]

Spec (files relative to the spec; every key but "models", "node" and one of "grid"/"poses" optional):
{
  "title": "...",
  "workspace": {
    "models": [{"key": "lumped", "file": "models/generated_lumped.json", "label": "generated VJM"},
               {"key": "beam", "file": "models/beam.json", "label": "beam"}],
    "reference": "beam",            the model the others are compared with (default: the last)
    "node": "E",                    the node whose compliance is compared (the end point, the platform)
    "directions": [[1, 0, 0], [0, 1, 0]],   force directions of the per-direction stiffness (default x, y, z)
    "load_case": "default",         the load of the loaded compliance and of the critical load
    "set": {"/loads/0/force/1": -300.0},   JSON pointers set in every model (here: the load)
    "pose": {"nodes": [{"node": "E", "xyz": [0.1, 0.37, 0]}]},   set in every model before the axes
    "grid": [{"name": "x", "pointer": "/pose/nodes/0/xyz/0", "values": [...]},
             {"name": "y", "pointer": "/pose/nodes/0/xyz/1", "values": [...]}],
    "poses": [{"id": "P1", "pose": {"joints": {"act1": 0.1}}}, ...]    instead of "grid"
  }
}
A grid's poses are the Cartesian product of its axes (the last fastest), each axis setting its
JSON pointer(s) in every model, as a sweep does (docs/sweep.md); "pose" values of a list replace
the models' "pose".

Per pose, each model runs three analyses in place of its own: "stiffness" of the node (unloaded),
"stiffness" with the load case (the loaded-mode compliance, linearised about the posed geometry)
and "buckling" with the load case (the critical load factor). The table then has, for every model
but the reference, the relative compliance differences

  dC_t = ||C_tt - C_tt,ref||_F / ||C_tt,ref||_F   (3x3 translational block of the 6x6 compliance)
  dC_r   the same for the rotational block,

unloaded (dC0_*) and loaded (dCL_*), the stiffness along each direction (indices.along) of every
model and its relative difference, and the critical load factors and their relative difference.
A pose a model cannot take (beyond reach, singular) gets its status in the row and no numbers.
Where the load case exceeds a model's critical load (a factor at most 1) the loaded stiffness is not
positive definite: the table keeps its numbers, the map leaves those poses out (marked +).

Writes OUT/workspace.csv (one row per pose), OUT/workspace.json (the same, with the compliances)
and OUT/workspace.png (a grid of two axes: maps of the differences; else curves along the list).
"""
import argparse
import copy
import csv
import itertools
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from find_beamfea import import_beamfea  # noqa: E402

# A planar linkage modelled in 3-D has redundant closure rows; beamfea says so once per run.
warnings.filterwarnings("ignore", message=".*constraint rows are redundant.*")


def load(path):
    with open(path) as f:
        return json.load(f)


def set_pointer(doc, pointer, value):
    """Sets the JSON pointer (RFC 6901) in doc, creating missing object members on the way."""
    parts = [p.replace("~1", "/").replace("~0", "~") for p in pointer.split("/")[1:]]
    node = doc
    for p in parts[:-1]:
        if isinstance(node, list):
            node = node[int(p)]
        else:
            node = node.setdefault(p, {})
    if isinstance(node, list):
        node[int(parts[-1])] = value
    else:
        node[parts[-1]] = value


def pose_list(ws):
    """[(pose id, {column: value}, [(pointer, value)] or None, pose dict or None)]."""
    if "grid" in ws:
        axes = ws["grid"]
        out = []
        for combo in itertools.product(*[range(len(a["values"])) for a in axes]):
            cols, sets = {}, []
            for a, i in zip(axes, combo):
                v = a["values"][i]
                cols[a.get("name", a["pointer"] if isinstance(a["pointer"], str) else a["pointer"][0])] = v
                for p in (a["pointer"] if isinstance(a["pointer"], list) else [a["pointer"]]):
                    sets.append((p, v))
            out.append(("_".join(f"{k}={v:g}" for k, v in cols.items()), cols, sets, None))
        return out
    return [(p.get("id", str(i)), {}, None, p.get("pose")) for i, p in enumerate(ws["poses"])]


def analyses(ws):
    node, lc = ws["node"], ws.get("load_case", "default")
    dirs = ws.get("directions", [[1, 0, 0], [0, 1, 0], [0, 0, 1]])
    return [{"id": "K0", "type": "stiffness", "node": node, "directions": dirs},
            {"id": "KL", "type": "stiffness", "node": node, "directions": dirs, "load_case": lc},
            {"id": "B", "type": "buckling", "modes": 1, "load_case": lc}]


class Runner:
    """beamfea.run in process (exe None) or the program `exe run --no-vtk`; (results, error)."""

    def __init__(self, exe):
        self.exe = exe
        self.bf = None if exe else import_beamfea()
        self.tmp = tempfile.mkdtemp(prefix="compare_workspace_") if exe else None

    def __call__(self, doc):
        if self.exe is None:
            try:
                return self.bf.run(doc, vtk=False), ""
            except self.bf.Error as e:
                return None, str(e).splitlines()[0]
        model = os.path.join(self.tmp, "model.json")
        with open(model, "w") as f:
            json.dump(doc, f)
        out = os.path.join(self.tmp, "out")
        p = subprocess.run([self.exe, "run", model, "--out", out, "--no-vtk", "-q"], capture_output=True, text=True)
        if p.returncode == 2 or not os.path.exists(os.path.join(out, "results.json")):
            msg = [ln for ln in (p.stderr + p.stdout).splitlines() if ln.strip() and "warning" not in ln]
            return None, (msg[-1] if msg else f"exit {p.returncode}").replace("beamfea: ", "")
        return load(os.path.join(out, "results.json")), ""


def extract(res):
    """What one model gives at one pose: compliances, stiffness along the directions, critical load."""
    a = res["analyses"]
    q = {}
    for key, aid in (("0", "K0"), ("L", "KL")):
        k = a.get(aid, {})
        if k.get("status", "ok") != "ok" or "compliance" not in k:
            q["status"] = f"{aid}: {k.get('message', k.get('status', 'missing'))}"
            continue
        C = np.asarray(k["compliance"], dtype=float)
        if not k.get("compliance_bounded", True):
            C = np.full((6, 6), np.nan)  # a free direction: no finite compliance to compare
        q["C" + key] = C
        q["along" + key] = [np.nan if v is None else float(v) for v in k.get("indices", {}).get("along", [])]
    b = a.get("B", {})
    lf = b.get("load_factors")
    q["lambda"] = float(lf[0]) if lf is not None and len(lf) else np.nan
    return q


def rel_block(C, R, block):
    s = slice(0, 3) if block == "t" else slice(3, 6)
    d = np.linalg.norm(R[s, s])
    return float(np.linalg.norm(C[s, s] - R[s, s]) / d) if d > 0 else np.nan


def rel(a, b):
    return (a - b) / b if b and np.isfinite(a) and np.isfinite(b) else np.nan


def compare(spec, base, out, exe, log=lambda s: print(s, file=sys.stderr, flush=True)):
    ws = spec["workspace"]
    models = ws["models"]
    ref = ws.get("reference", models[-1]["key"])
    docs = {}
    for m in models:
        d = load(os.path.join(base, m["file"]))
        d["analyses"] = analyses(ws)
        for p, v in ws.get("set", {}).items():
            set_pointer(d, p, v)
        if "pose" in ws:
            d["pose"] = copy.deepcopy(ws["pose"])
        docs[m["key"]] = d
    ndir = len(ws.get("directions", [[1, 0, 0], [0, 1, 0], [0, 0, 1]]))
    run = Runner(exe)
    poses = pose_list(ws)
    rows, full = [], []
    for i, (pid, cols, sets, pose) in enumerate(poses):
        vals = {}
        for key, d0 in docs.items():
            d = copy.deepcopy(d0)
            if pose is not None:
                d["pose"] = pose
            for p, v in sets or []:
                set_pointer(d, p, v)
            res, err = run(d)
            vals[key] = extract(res) if res else {"status": err}
        row = {"pose": pid, **cols}
        R = vals[ref]
        for key, q in vals.items():
            row[f"status_{key}"] = q.get("status", "ok")
            row[f"lambda_{key}"] = q.get("lambda", np.nan)
            for j in range(ndir):
                for L in ("0", "L"):
                    al = q.get("along" + L, [])
                    row[f"k{L}_{j}_{key}"] = al[j] if j < len(al) else np.nan
        for key, q in vals.items():
            if key == ref:
                continue
            for L in ("0", "L"):
                ok = "C" + L in q and "C" + L in R
                for b in ("t", "r"):
                    row[f"dC{L}_{b}_{key}"] = rel_block(q["C" + L], R["C" + L], b) if ok else np.nan
                for j in range(ndir):
                    row[f"dk{L}_{j}_{key}"] = rel(row[f"k{L}_{j}_{key}"], row[f"k{L}_{j}_{ref}"])
            row[f"dlambda_{key}"] = rel(row[f"lambda_{key}"], row[f"lambda_{ref}"])
        rows.append(row)
        full.append({"pose": pid, "parameters": cols,
                     "models": {k: {"status": q.get("status", "ok"),
                                    **{n: (q[n].tolist() if isinstance(q.get(n), np.ndarray) else q.get(n))
                                       for n in ("C0", "CL", "along0", "alongL", "lambda")}} for k, q in vals.items()}})
        if (i + 1) % 10 == 0 or i + 1 == len(poses):
            log(f"  {i + 1}/{len(poses)} poses")
    if run.tmp:
        shutil.rmtree(run.tmp, ignore_errors=True)
    os.makedirs(out, exist_ok=True)
    columns = list(rows[0]) if rows else []
    with open(os.path.join(out, "workspace.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) and math.isfinite(v) else "" if isinstance(v, float) else v)
                        for k, v in r.items()})
    with open(os.path.join(out, "workspace.json"), "w") as f:
        json.dump({"title": spec.get("title", ""), "reference": ref, "poses": full}, f, indent=1,
                  default=lambda x: None)
    return rows


def beyond_critical(row, *keys):
    """True where the load case exceeds a model's critical load (a factor in (0, 1])."""
    lam = [row.get(f"lambda_{k}") for k in keys]
    return any(isinstance(v, float) and math.isfinite(v) and 0.0 < v <= 1.0 for v in lam)


def plot(spec, rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ws = spec["workspace"]
    ref = ws.get("reference", ws["models"][-1]["key"])
    others = [m for m in ws["models"] if m["key"] != ref]
    key = others[0]["key"]
    label = f"{others[0].get('label', key)} vs {next(m.get('label', ref) for m in ws['models'] if m['key'] == ref)}"
    panels = [(f"dC0_t_{key}", "unloaded compliance\n||dC_tt|| / ||C_tt|| (%)"),
              (f"dCL_t_{key}", "loaded compliance\n||dC_tt|| / ||C_tt|| (%)"),
              (f"dlambda_{key}", f"critical load factor\n({key} - {ref}) / {ref} (%)")]
    val = lambda r, c: 100.0 * r[c] if isinstance(r.get(c), float) else np.nan
    grid = ws.get("grid", [])
    fig, axs = plt.subplots(1, 3, figsize=(12.5, 3.9))
    if len(grid) == 2:
        n0, n1 = (a.get("name", a["pointer"]) for a in grid)
        x0, x1 = np.asarray(grid[0]["values"], float), np.asarray(grid[1]["values"], float)
        for ax, (c, title) in zip(axs, panels):
            Z = np.array([val(r, c) for r in rows]).reshape(len(x0), len(x1))
            if c.startswith("dCL"):
                # Beyond the critical load (a factor below 1) the loaded stiffness is not positive
                # definite: no loaded compliance to compare there.
                above = [beyond_critical(r, key, ref) for r in rows]
                Z[np.array(above).reshape(Z.shape)] = np.nan
                pts = [(r[n0], r[n1]) for r, a in zip(rows, above) if a]
                if pts:
                    ax.plot(*zip(*pts), "k+", ms=6, label="load above the critical load")
            lim = np.nanmax(np.abs(Z)) if np.isfinite(Z).any() else 1.0
            signed = np.nanmin(Z) < 0 if np.isfinite(Z).any() else False
            im = ax.pcolormesh(x0, x1, Z.T, shading="nearest", cmap="RdBu_r" if signed else "viridis",
                               vmin=-lim if signed else 0.0, vmax=lim)
            fig.colorbar(im, ax=ax)
            bad = [(r[n0], r[n1]) for r in rows if r.get(f"status_{key}") != "ok" or r.get(f"status_{ref}") != "ok"]
            if bad:
                ax.plot(*zip(*bad), "kx", ms=5, label="pose not reached")
            if ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2, frameon=False)
            ax.set_xlabel(n0)
            ax.set_ylabel(n1)
            ax.set_aspect("equal")
            ax.set_title(title, fontsize=9)
    else:
        xs = list(range(len(rows)))
        for ax, (c, title) in zip(axs, panels):
            ys = [np.nan if c.startswith("dCL") and beyond_critical(r, key, ref) else val(r, c) for r in rows]
            ax.plot(xs, ys, "o-")
            ax.set_xticks(xs, [r["pose"] for r in rows], rotation=45, fontsize=7)
            ax.set_title(title, fontsize=9)
            ax.grid(alpha=0.3)
    fig.suptitle(f"{spec.get('title', '')}: {label}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90, bbox_inches="tight")
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("spec")
    ap.add_argument("--beamfea", default=None, help="run this beamfea program (default: the Python module, in process)")
    ap.add_argument("--out", default="comparison")
    ap.add_argument("--no-plots", action="store_true")
    args = ap.parse_args(argv)
    spec = load(args.spec)
    base = os.path.dirname(os.path.abspath(args.spec))
    exe = os.path.abspath(args.beamfea) if args.beamfea else None
    rows = compare(spec, base, args.out, exe)
    if not args.no_plots and rows:
        plot(spec, rows, os.path.join(args.out, "workspace.png"))
    print(f"wrote {args.out}/workspace.csv, workspace.json" + ("" if args.no_plots else ", workspace.png"),
          file=sys.stderr)


if __name__ == "__main__":
    main()
