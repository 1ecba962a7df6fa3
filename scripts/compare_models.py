#!/usr/bin/python3
"""Comparison report: lumped (VJM) models against their beam counterparts, side by side.

A *comparison spec* (JSON) lists pairs (or groups) of beamfea model files that describe the same
structure in different ways, and the quantities to compare. For every pair this driver runs
beamfea on each model, extracts the force-deflection curve of the path analysis, its critical
points and stability, the loaded stiffness, and writes

  OUT/summary.md, OUT/summary.csv   one table: every quantity, every model, the fixed columns
                                    of the spec ("paper", "reference", ...)
  OUT/<pair>/<model>.csv            the curve: deflection, force, stable, negative eigenvalues,
                                    smallest eigenvalue, tangent stiffness
  OUT/<pair>.png                    force-deflection curves of all models of the pair, stable
                                    parts solid, unstable dashed, critical points marked
  OUT/<pair>/<model>/               beamfea's own output: results.json and the ParaView series
                                    <path id>.pvd of the path (when the engine writes it)

Spec format (every key but "pairs" optional):
{
  "title": "...",
  "path_analysis": "path",                       id of the path analysis in each model file
  "force": {"from": "load_factor", "scale": 1, "label": "P"},
  "deflection": {"node": "E", "dof": "ux", "scale": -1, "label": "delta"},
  "stiffness_node": "E",     unloaded stiffness: the model with this node's supports and all loads
                             removed, by beamfea's "stiffness" analysis (entry dof, dof)
  "quantities": ["critical_force", "unloaded", "near_before", "near_after", "large", "P_at_L"],
  "large_deflection": 1.0,   deflection of the "large deformation" quantities
  "near_offset": 1e-3,       how far from the critical point "near buckling" tangents are taken
  "loaded_at": 1.0,          load factor of the "loaded_compliance" quantity
  "pairs": [{"id": "B_S", "name": "model B, S posture",
             "models": [{"key": "lumped", "file": "models/B_S_lumped.json", "label": "VJM"},
                        {"key": "beam", "file": "models/B_S_beam.json", "label": "beam"}],
             "values": {"paper": {"critical_force": 1.0, ...}, "reference": {...}},
             "reference_curve": {"label": "...", "points": [[delta, P], ...]}}]
}
(The short form {"lumped": {...}, "beam": {...}} of a pair is accepted too.)

Quantities (tangents k = dP/d(deflection) of the displacement-controlled curve, on the stable branch):
  critical_force  force at the first critical point (engine's critical_points[]);
                  "path failed" when the path stopped on non-convergence before finding one
  buckling_load   the first load factor of the model's "buckling" analysis, when it has one
                  (linearised about the unloaded state: the critical force of a straight chain)
  unloaded        stiffness at zero load
  near_before     tangent just before the first critical point (last two stable steps before it)
  near_after      tangent just after it, on the stable branch followed (first two stable steps
                  beyond it by more than near_offset; at a bifurcation only if the engine switched)
  large           tangent at the large deflection
  P_at_L          force at the large deflection
  unloaded_compliance  compliance (entry dof, dof) of beamfea's "stiffness" at zero load: finite for a
                  node whose motion closed loops restrict (the end point of a parallel manipulator),
                  inf where the node moves freely along dof (its "unbounded_directions")
  loaded_compliance    the path's loaded compliance (entry dof, dof) at the step nearest to the load
                  factor "loaded_at" (default 1.0) before the first critical point (interpolated
                  linearly between the two steps around it)

A spec with a "workspace" key instead of "pairs" compares the models pose by pose over a list or a
grid of poses (compliance differences, unloaded and loaded, and critical loads): see
scripts/compare_workspace.py, which this driver hands such a spec to.

Files are relative to the spec. Run:
  /usr/bin/python3 scripts/compare_models.py SPEC --out OUT [--only ID ...]
runs the models in process with the Python module (beamfea.run, docs/python.md: an installed
beamfea or the one built in build/python); with --beamfea build/cli/beamfea it runs the program
instead (the same engine, the same numbers). Either way OUT/<pair>/<model>/ receives beamfea's files.
When an analysis type is missing from the beamfea used, the models are run without it and the
report says what is missing; nothing is invented.
"""
import argparse
import copy
import csv
import json
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from find_beamfea import import_beamfea  # noqa: E402

DOFS = ["ux", "uy", "uz", "rx", "ry", "rz"]


def nonempty(x):
    """True for a non-empty list or NumPy array (results from the module hold arrays)."""
    return x is not None and len(x) > 0


def load(path):
    with open(path) as f:
        return json.load(f)


REUSE = False  # --reuse: keep results.json of an earlier run of the very same model


def run_beamfea(exe, doc, out_dir, log):
    """Runs beamfea on doc, in process (exe None: the Python module) or with the program `exe`;
    drops analyses of a type this beamfea does not know. Writes OUT files into out_dir either
    way. Returns (results or None, [missing types], error message)."""
    os.makedirs(out_dir, exist_ok=True)
    model_file, res_file = os.path.join(out_dir, "model.json"), os.path.join(out_dir, "results.json")
    if REUSE and os.path.exists(model_file) and os.path.exists(res_file) and load(model_file) == doc:
        return load(res_file), [], ""
    missing = []
    doc = copy.deepcopy(doc)
    for _ in range(5):
        model_file = os.path.join(out_dir, "model.json")
        with open(model_file, "w") as f:
            json.dump(doc, f, indent=1)
        if exe is None:
            res, unknown, err = _run_module(doc, out_dir)
        else:
            res, unknown, err = _run_program(exe, model_file, out_dir)
        if unknown:
            missing.append(unknown)
            doc["analyses"] = [a for a in doc.get("analyses", []) if a.get("type") != unknown]
            log(f"    beamfea has no analysis '{unknown}': running without it")
            continue
        return res, missing, err
    return None, missing, "too many missing analysis types"


def _run_module(doc, out_dir):
    """(results or None, unknown analysis type or None, error message) of beamfea.run."""
    bf = import_beamfea()
    try:
        res = bf.run(doc, out=out_dir)
    except bf.InputError as e:
        m = re.search(r"unknown type '([^']+)'", str(e))
        if m and (e.pointer or "").startswith("/analyses"):
            return None, m.group(1), ""
        return None, None, str(e)
    except bf.Error as e:
        return None, None, str(e)
    failed = [f"{k}: {a.get('message', a.get('status'))}" for k, a in res.get("analyses", {}).items()
              if isinstance(a, dict) and a.get("status", "ok") != "ok"]
    return res, None, failed[-1] if failed else ""


def _run_program(exe, model_file, out_dir):
    """The same with the program: `exe run model_file --out out_dir`."""
    p = subprocess.run([exe, "run", model_file, "--out", out_dir], capture_output=True, text=True)
    with open(os.path.join(out_dir, "beamfea.log"), "w") as f:
        f.write(p.stdout + p.stderr)
    m = re.search(r"unknown type '([^']+)'", p.stderr + p.stdout)
    if m and "analys" in (p.stderr + p.stdout):
        return None, m.group(1), ""
    res_file = os.path.join(out_dir, "results.json")
    if os.path.exists(res_file):
        return load(res_file), None, (p.stderr.strip().splitlines() or [""])[-1] if p.returncode else ""
    return None, None, (p.stderr.strip() or p.stdout.strip())[-500:]


UNLOADED_COMPLIANCE = {}  # out_dir -> compliance entry of the last unloaded_stiffness run there


def unloaded_stiffness(exe, doc, node, dof, out_dir, log):
    d = copy.deepcopy(doc)
    d["supports"] = [s for s in d.get("supports", []) if s.get("node") != node]
    d["prescribed"] = [s for s in d.get("prescribed", []) if s.get("node") != node]
    d.pop("loads", None)
    d["analyses"] = [{"id": "K", "type": "stiffness", "node": node}]
    res, _, err = run_beamfea(exe, d, out_dir, log)
    if not res or "K" not in res.get("analyses", {}):
        # beamfea refuses a node that the constraints fix (a rigid straight chain): unbounded.
        return (math.inf, err) if "unbounded" in err else (None, err)
    a = res["analyses"]["K"]
    if a.get("status") != "ok":
        return math.inf, a.get("message", "")  # e.g. a rigid straight chain: unbounded
    if nonempty(a.get("compliance")):
        UNLOADED_COMPLIANCE[out_dir] = compliance_entry(a, dof)
    if in_span(dof, a.get("rigid_directions")):
        return math.inf, ""  # the node cannot move along dof (e.g. a rigid straight chain): unbounded
    return a["matrix"][dof][dof], ""


def compliance_entry(a, dof):
    """compliance (dof, dof); inf along an unbounded direction (where "compliance" holds 0)."""
    free = any(abs(v[dof]) > 1e-9 for v in a.get("unbounded_directions", []))
    return math.inf if free else a["compliance"][dof][dof]


def in_span(dof, vectors, tol=1e-9):
    """True when the unit vector of `dof` lies in the span of `vectors` (Gram-Schmidt, pure Python)."""
    basis = []
    for v in (vectors if vectors is not None else []):
        w = [float(x) for x in v]
        for b in basis:
            d = sum(x * y for x, y in zip(w, b))
            w = [x - d * y for x, y in zip(w, b)]
        n = math.sqrt(sum(x * x for x in w))
        if n > 1e-12:
            basis.append([x / n for x in w])
    proj = sum(b[dof] ** 2 for b in basis)
    return proj > 1.0 - tol


class Curve:
    def __init__(self):
        self.d, self.P, self.stable, self.neg, self.mineig, self.k, self.lf = [], [], [], [], [], [], []
        self.comp = []       # the path's loaded compliance entry (dof, dof) per step, or None
        self.critical = []   # (deflection, force, type)
        self.termination = ""
        self.buckling = []   # load factors of a "buckling" analysis
        self.completed = False
        self.switched = []   # per critical point: the path switched onto another branch there
        self.critical_step = []


def extract_curve(res, spec):
    c = Curve()
    pa = spec.get("path_analysis", "path")
    node = spec["deflection"]["node"]
    dof = DOFS.index(spec["deflection"].get("dof", "ux"))
    ds = spec["deflection"].get("scale", 1.0)
    fs = spec.get("force", {}).get("scale", 1.0)
    analyses = res.get("analyses", {})
    for a in analyses.values():
        if a.get("type") == "buckling" and nonempty(a.get("load_factors")):
            c.buckling = [fs * x for x in a["load_factors"]]
    a = analyses.get(pa)
    if not a or "steps" not in a:
        return None if not c.buckling else c
    for s in a["steps"]:
        c.d.append(ds * s["nodes"][node]["displacement"][dof])
        c.lf.append(s["load_factor"])
        c.P.append(fs * s["load_factor"])
        c.stable.append(bool(s.get("stable", True)))
        c.neg.append(s.get("negative_eigenvalues", ""))
        c.mineig.append(s.get("min_eigenvalue", ""))
        k = s.get("stiffness")
        # The engine's loaded stiffness entry dF/du of the node; the deflection and the force are
        # assumed measured along the same direction (both scales of the same sign), so dP/dd = dF/du.
        c.k.append(k[dof][dof] if nonempty(k) else None)
        c.comp.append(compliance_entry(s, dof) if nonempty(s.get("compliance")) else None)
    for cp in a.get("critical_points", []):
        # the step at whose end the engine detected it; the critical point lies between that step
        # and the one before, at the critical load factor
        step = cp.get("step")
        dcp = None
        if step is not None and 1 <= step < len(c.d):
            l0, l1 = c.lf[step - 1], c.lf[step]
            t = 0.0 if l1 == l0 else min(1.0, max(0.0, (cp["load_factor"] - l0) / (l1 - l0)))
            dcp = c.d[step - 1] + t * (c.d[step] - c.d[step - 1])
        c.critical.append((dcp, fs * cp["load_factor"], cp.get("type", "")))
        c.switched.append(bool(cp.get("branch_switched", False)))
        c.critical_step.append(step)
    c.termination = a.get("termination", "")
    c.completed = bool(a.get("completed", a.get("status") == "ok"))
    return c


def interp(x, xs, ys):
    for i in range(1, len(xs)):
        a, b = xs[i - 1], xs[i]
        if (a - x) * (b - x) <= 0 and a != b:
            t = (x - a) / (b - a)
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return None


def tangent_at(c, x, side=0, stable_only=True):
    """dP/dd at deflection x: the engine's loaded stiffness where given, else a difference quotient
    of neighbouring converged steps. side < 0: from steps before x, > 0: after."""
    idx = [i for i in range(len(c.d)) if (c.stable[i] or not stable_only)]
    if not idx:
        return None
    if side < 0:
        cand = [i for i in idx if c.d[i] <= x]
        if not cand:
            return None
        i = max(cand, key=lambda j: c.d[j])
    elif side > 0:
        cand = [i for i in idx if c.d[i] >= x]
        if not cand:
            return None
        i = min(cand, key=lambda j: c.d[j])
    else:
        i = min(idx, key=lambda j: abs(c.d[j] - x))
    if c.k[i] is not None:
        return c.k[i]
    # difference quotient with the adjacent step on the same side of the branch
    j = i - 1 if (side < 0 or i + 1 >= len(c.d)) else i + 1
    if j < 0 or c.d[j] == c.d[i]:
        return None
    return (c.P[j] - c.P[i]) / (c.d[j] - c.d[i])


def slope(c, idx, last):
    """dP/dd between two consecutive converged steps of the list idx (the last two, or the first two);
    the engine's loaded stiffness of the step where it gives one."""
    if len(idx) < 2:
        return None
    i, j = (idx[-2], idx[-1]) if last else (idx[0], idx[1])
    k = c.k[j] if last else c.k[i]
    if k is not None:
        return k
    if j != i + 1 or c.d[j] == c.d[i]:
        return None
    return (c.P[j] - c.P[i]) / (c.d[j] - c.d[i])


def quantities(c, k0, spec):
    q = {"unloaded": k0}
    if c is None:
        return q
    if c.buckling:
        q["buckling_load"] = c.buckling[0]
    large = spec.get("large_deflection", 1.0)
    off = spec.get("near_offset", 1e-3)
    if c.critical:
        dcr, pcr, _ = c.critical[0]
        # A critical point found before the path failed is still the engine's result; say so.
        q["critical_force"] = pcr if c.completed else f"{pcr:.4g} (path failed later)"
        step = c.critical_step[0]
        if step is not None and c.d:
            q["near_before"] = slope(c, [i for i in range(step) if c.stable[i]], last=True)
            # after a bifurcation: only on the branch the engine switched to (the fundamental
            # branch beyond it is unstable and not the curve of the paper)
            if c.critical[0][2] != "bifurcation" or c.switched[0]:
                d0 = c.d[step - 1] if step >= 1 else 0.0
                after = [i for i in range(step, len(c.d)) if c.stable[i] and c.d[i] > d0 + off]
                q["near_after"] = slope(c, after, last=False)
            else:
                q["near_after"] = "no branch switch"
    elif c.d and c.completed:
        q["critical_force"] = None  # no critical point on the path
    elif c.d:
        q["critical_force"] = "path failed"
    if c.d and max(c.d) >= large - 1e-9:
        q["P_at_L"] = interp(large, c.d, c.P)
        q["large"] = tangent_at(c, large, side=0, stable_only=False)
    elif c.d and not c.completed:
        q["P_at_L"] = q["large"] = "path failed"
    at = spec.get("loaded_at", 1.0)
    # On the primary branch: before the first critical point (the load factor may pass `at` again after it).
    first = c.critical_step[0] if c.critical_step and c.critical_step[0] is not None else len(c.lf)
    with_c = [i for i in range(min(first, len(c.lf))) if c.comp[i] is not None]
    if with_c:
        q["loaded_compliance"] = c.comp[min(with_c, key=lambda j: abs(c.lf[j] - at))]
        for i, j in zip(with_c, with_c[1:]):  # linear interpolation between the steps around `at`
            if j == i + 1 and (c.lf[i] - at) * (c.lf[j] - at) <= 0 and c.lf[i] != c.lf[j]:
                t = (at - c.lf[i]) / (c.lf[j] - c.lf[i])
                q["loaded_compliance"] = c.comp[i] + t * (c.comp[j] - c.comp[i])
                break
    return q


def fmt(v):
    if v is None:
        return "—"
    if isinstance(v, str):
        return v
    if math.isinf(v):
        return "∞"
    a = abs(v)
    if a >= 100:
        return f"{v:.0f}"
    if a >= 1:
        return f"{v:.4f}"
    return f"{v:.4g}"


def write_curve_csv(path, c):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["deflection", "force", "stable", "negative_eigenvalues", "min_eigenvalue", "tangent_stiffness"])
        for i in range(len(c.d)):
            w.writerow([c.d[i], c.P[i], int(c.stable[i]), c.neg[i], c.mineig[i], "" if c.k[i] is None else c.k[i]])


def plot_pair(path, pair, curves, spec):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.2))
    colors = ["C0", "C3", "C2", "C1", "C4"]
    for (label, c), col in zip(curves, colors):
        if c is None or not c.d:
            continue
        # stable parts solid, unstable dashed
        start = 0
        for i in range(1, len(c.d) + 1):
            if i == len(c.d) or c.stable[i] != c.stable[start]:
                seg = slice(max(0, start - 1) if start else 0, i)
                ax.plot(c.d[seg], c.P[seg], "-" if c.stable[start] else "--", color=col,
                        label=label if start == 0 else None)
                start = i
        for dcr, pcr, typ in c.critical:
            if dcr is not None:
                ax.plot([dcr], [pcr], "o", mfc="none", color=col, ms=8)
                ax.annotate(f"{typ} {pcr:.3f}", (dcr, pcr), textcoords="offset points", xytext=(5, -12),
                            fontsize=7, color=col)
    rc = pair.get("reference_curve")
    if rc:
        xs, ys = zip(*rc["points"])
        ax.plot(xs, ys, "k+", ms=8, label=rc.get("label", "reference"))
    ax.set_xlabel(spec["deflection"].get("label", "deflection"))
    ax.set_ylabel(spec.get("force", {}).get("label", "force"))
    ax.set_title(pair.get("name", pair["id"]), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def normalise_pair(p):
    if "models" not in p:
        p = dict(p)
        p["models"] = [dict(p[k], key=k) for k in ("lumped", "beam") if k in p]
    if "values" not in p:
        p["values"] = {k: p[k] for k in ("paper", "reference") if k in p}
    return p


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("spec")
    ap.add_argument("--beamfea", default=None,
                    help="run this beamfea program (default: the Python module, in process)")
    ap.add_argument("--out", default="comparison")
    ap.add_argument("--only", nargs="*", default=None, help="pair ids to run")
    ap.add_argument("--no-plots", action="store_true")
    ap.add_argument("--reuse", action="store_true", help="reuse OUT's results of unchanged models (no beamfea run)")
    args = ap.parse_args()
    global REUSE
    REUSE = args.reuse
    spec = load(args.spec)
    if "workspace" in spec:  # pose by pose over a workspace: scripts/compare_workspace.py
        import compare_workspace
        return compare_workspace.main([args.spec, "--out", args.out] + (["--beamfea", args.beamfea] if args.beamfea else [])
                                      + (["--no-plots"] if args.no_plots else []))
    base = os.path.dirname(os.path.abspath(args.spec))
    exe = os.path.abspath(args.beamfea) if args.beamfea else None
    os.makedirs(args.out, exist_ok=True)
    qnames = spec.get("quantities", ["critical_force", "unloaded", "near_before", "near_after", "large", "P_at_L"])
    node = spec.get("stiffness_node", spec["deflection"]["node"])
    dof = DOFS.index(spec["deflection"].get("dof", "ux"))
    log = lambda s: print(s, file=sys.stderr, flush=True)
    rows, missing_all, summary, terminations = [], set(), {}, []
    for pair in map(normalise_pair, spec["pairs"]):
        if args.only and pair["id"] not in args.only:
            continue
        log(f"{pair['id']}: {pair.get('name', '')}")
        pdir = os.path.join(args.out, pair["id"])
        os.makedirs(pdir, exist_ok=True)
        curves, qs = [], {}
        for m in pair["models"]:
            doc = load(os.path.join(base, m["file"]))
            mdir = os.path.join(pdir, m["key"])
            log(f"  {m['key']}: {m['file']}")
            k0, kerr = unloaded_stiffness(exe, doc, node, dof, os.path.join(mdir, "unloaded"), log)
            res, missing, err = run_beamfea(exe, doc, mdir, log)
            missing_all.update(missing)
            c = extract_curve(res, spec) if res else None
            if err:
                log(f"    beamfea: {err}")
            if c is not None and c.d:
                write_curve_csv(os.path.join(pdir, f"{m['key']}.csv"), c)
                pvds = [f for f in os.listdir(mdir) if f.endswith(".pvd")]
                log(f"    {len(c.d)} steps, critical points {[(round(x[1], 5), x[2]) for x in c.critical]}, "
                    f"termination: {c.termination}; ParaView: {pvds}")
            if c is not None and c.d:
                terminations.append((pair["id"], m["key"], len(c.d), "ok" if c.completed else "FAILED", c.termination))
            qs[m["key"]] = quantities(c, k0, spec)
            qs[m["key"]]["unloaded_compliance"] = UNLOADED_COMPLIANCE.get(os.path.join(mdir, "unloaded"))
            qs[m["key"]]["_missing"] = missing
            curves.append((m.get("label", m["key"]), c))
        if not args.no_plots and any(c is not None and c.d for _, c in curves):
            plot_pair(os.path.join(args.out, f"{pair['id']}.png"), pair, curves, spec)
        summary[pair["id"]] = {k: {q: v for q, v in d.items()} for k, d in qs.items()}
        for q in qnames:
            row = {"pair": pair["id"], "quantity": q}
            for m in pair["models"]:
                v = qs[m["key"]].get(q, "missing" if qs[m["key"]]["_missing"] else None)
                row[m["key"]] = v
            for vk, vals in pair["values"].items():
                row[vk] = vals.get(q)
            rows.append(row)
    # Tables
    cols = []
    for r in rows:
        for k in r:
            if k not in cols:
                cols.append(k)
    with open(os.path.join(args.out, "summary.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in cols})
    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write(f"# {spec.get('title', 'Comparison report')}\n\n")
        if missing_all:
            f.write(f"**Missing in this beamfea: analyses {sorted(missing_all)}.** The curve quantities of models "
                    "that need them are marked 'missing'; nothing was estimated in their place.\n\n")
        f.write("| " + " | ".join(cols) + " |\n|" + "---|" * len(cols) + "\n")
        for r in rows:
            f.write("| " + " | ".join(fmt(r.get(k)) if k not in ("pair", "quantity") else r[k] for k in cols) + " |\n")
        if terminations:
            f.write("\nPath analyses (converged steps, outcome, beamfea's termination message):\n\n"
                    "| pair | model | steps | outcome | termination |\n|---|---|---|---|---|\n")
            for t in terminations:
                f.write("| " + " | ".join(str(x) for x in t) + " |\n")
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1, default=str)
    log(f"wrote {args.out}/summary.md, summary.csv, summary.json")


if __name__ == "__main__":
    main()
