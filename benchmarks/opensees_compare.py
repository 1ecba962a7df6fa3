#!/usr/bin/env python3
"""beamfea vs OpenSees on the same linear static model (a regular 3-D space frame).

Needs OpenSeesPy (PyPI `openseespy`, not a Debian package, so it is not part of the build):
    python3 -m venv /tmp/ops && /tmp/ops/bin/pip install openseespy
    /tmp/ops/bin/python benchmarks/opensees_compare.py --beamfea build/cli/beamfea --sizes 4,8,12

For each size it writes the frame as a beamfea model, runs `beamfea run --no-vtk` and reads the
analysis' own wall time from results.json (DOF map, assembly, factorisation, solve, reactions,
end forces), then builds the same model in OpenSees (elasticBeamColumn, Linear transformation with
the same vecxz, Plain constraints, RCM numberer, each sparse system in turn) and times
`analyze(1)` + `reactions()`. Both answers are compared (roof displacement) before any time is
reported. Times are the minimum of --repeat runs, in one session on one machine.
"""
import argparse, json, os, subprocess, sys, tempfile, time

def frame(n, stories=None):
    nx = ny = n
    nz = stories or n
    bx, by, h = 6.0, 6.0, 3.5
    nodes, elems, supports, loads = [], [], [], []
    def nid(i, j, k): return (k * (ny + 1) + j) * (nx + 1) + i + 1
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                nodes.append((nid(i, j, k), i * bx, j * by, k * h))
                if k == 0:
                    supports.append(nid(i, j, k))
                elif (i + j + k) % 2 == 0:
                    loads.append((nid(i, j, k), 1e3, 0.5e3, -10e3))
    for k in range(nz):
        for j in range(ny + 1):
            for i in range(nx + 1):
                elems.append((nid(i, j, k), nid(i, j, k + 1), "col", (1.0, 0.0, 0.0)))
    for k in range(1, nz + 1):
        for j in range(ny + 1):
            for i in range(nx):
                elems.append((nid(i, j, k), nid(i + 1, j, k), "beam", (0.0, 0.0, 1.0)))
        for j in range(ny):
            for i in range(nx + 1):
                elems.append((nid(i, j, k), nid(i, j + 1, k), "beam", (0.0, 0.0, 1.0)))
    return nodes, elems, supports, loads

SECTIONS = {"col": dict(A=7.81e-3, Iy=5.696e-5, Iz=2.003e-5, J=5.93e-7),
            "beam": dict(A=5.38e-3, Iy=8.356e-5, Iz=6.04e-6, J=2.0e-7)}
E, G = 2.1e11, 8.077e10

def beamfea_model(nodes, elems, supports, loads):
    return {
        "nodes": [{"id": n, "xyz": [x, y, z]} for n, x, y, z in nodes],
        "materials": [{"id": "s", "E": E, "G": G}],
        "sections": [dict(id=k, **v) for k, v in SECTIONS.items()],
        "elements": [{"id": e + 1, "type": "beam", "nodes": [a, b], "material": "s", "section": s, "orientation": list(o)}
                     for e, (a, b, s, o) in enumerate(elems)],
        "supports": [{"node": n, "fix": "all"} for n in supports],
        "loads": [{"node": n, "force": [fx, fy, fz]} for n, fx, fy, fz in loads],
        "analyses": [{"id": "lin", "type": "linear_static"}],
    }

def run_beamfea(exe, model, probe):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "m.json")
        with open(path, "w") as f:
            json.dump(model, f)
        t0 = time.perf_counter()
        subprocess.run([exe, "run", path, "--out", os.path.join(d, "out"), "--no-vtk", "-q"], check=True)
        total = time.perf_counter() - t0
        res = json.load(open(os.path.join(d, "out", "results.json")))["analyses"]["lin"]
        return res["wall_time_s"], total, res["nodes"][str(probe)]["displacement"][0], res["free_dofs"]

def run_opensees(nodes, elems, supports, loads, probe, system):
    import openseespy.opensees as ops
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    for n, x, y, z in nodes:
        ops.node(n, x, y, z)
    for n in supports:
        ops.fix(n, 1, 1, 1, 1, 1, 1)
    tags = {}
    for e, (a, b, s, o) in enumerate(elems):
        if o not in tags:
            tags[o] = len(tags) + 1
            ops.geomTransf("Linear", tags[o], *o)
        p = SECTIONS[s]
        ops.element("elasticBeamColumn", e + 1, a, b, p["A"], E, G, p["J"], p["Iy"], p["Iz"], tags[o])
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    for n, fx, fy, fz in loads:
        ops.load(n, fx, fy, fz, 0, 0, 0)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system(*system)
    ops.test("NormUnbalance", 1e-6, 1)
    ops.algorithm("Linear")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    t0 = time.perf_counter()
    ok = ops.analyze(1)
    ops.reactions()
    dt = time.perf_counter() - t0
    if ok != 0:
        raise RuntimeError(f"OpenSees {system} failed")
    return dt, ops.nodeDisp(probe, 1)

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--beamfea", default="build/cli/beamfea")
    ap.add_argument("--sizes", default="4,8,12")
    ap.add_argument("--stories", type=int, default=None)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--systems", default="UmfPack;SparseSYM;ProfileSPD")
    a = ap.parse_args()
    systems = [tuple(s.split()) for s in a.systems.split(";")]
    print("| bays | elements | free DOFs | beamfea analysis s | " + " | ".join(f"OpenSees {' '.join(s)} s" for s in systems)
          + " | best OpenSees / beamfea | roof ux agreement |")
    print("|---:|---:|---:|---:|" + "---:|" * len(systems) + "---:|---:|")
    for n in [int(s) for s in a.sizes.split(",")]:
        nodes, elems, supports, loads = frame(n, a.stories)
        probe = nodes[-1][0]
        model = beamfea_model(nodes, elems, supports, loads)
        bf = min((run_beamfea(a.beamfea, model, probe) for _ in range(a.repeat)), key=lambda r: r[0])
        row, best = [], None
        for s in systems:
            try:
                r = min((run_opensees(nodes, elems, supports, loads, probe, s) for _ in range(a.repeat)), key=lambda r: r[0])
                if abs(r[1] - bf[2]) > 1e-6 * abs(bf[2]):
                    raise RuntimeError(f"answers differ: {r[1]} vs {bf[2]}")
                row.append(f"{r[0]:.4g}")
                best = r[0] if best is None else min(best, r[0])
            except Exception as ex:  # a system OpenSeesPy lacks, or too slow
                row.append(f"n/a ({ex})"[:40])
        print(f"| {n}x{n}x{a.stories or n} | {len(elems)} | {bf[3]} | {bf[0]:.4g} | " + " | ".join(row)
              + f" | {best / bf[0]:.2f} | {bf[2]:.6e} |", flush=True)

if __name__ == "__main__":
    main()
