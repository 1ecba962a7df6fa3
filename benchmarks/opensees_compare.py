#!/usr/bin/env python3
"""beamfea vs OpenSees on the same linear static model (a regular 3-D space frame), on the same BLAS.

OpenSeesPy is a test-only tool, not a project dependency. OpenSeesPy 3.8 needs Python >= 3.12
(under 3.11 pip quietly installs 3.7.1):
    ~/.pyenv/versions/3.12.1/bin/python -m venv /tmp/ops312 && /tmp/ops312/bin/pip install 'openseespy==3.8.*'
    /tmp/ops312/bin/python benchmarks/opensees_compare.py --beamfea build/cli/beamfea \
        --sizes 15x15x14,25x25x24 --repeat 3

The OpenSeesPy 3.8 wheel carries its own reference BLAS (openseespylinux/lib/libblas.so.3) and
loads it whatever LD_LIBRARY_PATH says. An earlier version of this script ran OpenSees on that
BLAS and beamfea on OpenBLAS, which made beamfea look 1.4-2.2x faster for no reason of its own.
Here every OpenSees process is started with LD_PRELOAD=<--blas> (default: the system OpenBLAS),
and each side reports the BLAS it actually mapped, read from its own /proc/<pid>/maps.

Per size and repetition, in one sitting and interleaved (beamfea, then each OpenSees system,
the order rotated each repetition so that load drifts hit all sides alike):
  - beamfea: `beamfea run --no-vtk -q` as a child process; "process" is its whole wall time
    (reading and checking the JSON, analysis, writing results.json), "analysis" is the
    linear_static analysis' own wall_time_s from results.json (DOF map, assembly,
    factorisation, solve, reactions, end forces, results object).
  - OpenSees: a child Python process (this script, --opensees-child) that builds the same model
    through OpenSeesPy (elasticBeamColumn, Linear transformation with the same vecxz, Plain
    constraints, RCM numberer) and times analyze(1) + reactions() ("analysis"); "process" is the
    child's whole wall time (interpreter start, import, model definition, analysis; with
    --opensees-writes also writing the displacements, reactions and local end forces that
    beamfea's results.json holds, for equal output: without it OpenSees writes nothing).
Both answers are compared (roof displacement, 1e-6 relative) before any time is reported. The
table gives the median of each time and the median of the per-repetition paired ratios
OpenSees / beamfea (above 1: beamfea faster).
"""
import argparse, json, os, re, resource, statistics, subprocess, sys, tempfile, time

OPENBLAS = "/usr/lib/x86_64-linux-gnu/openblas-pthread/libblas.so.3"


def parse_size(s):
    """'n' (n x n x n bays) or 'nx x ny x nz'."""
    parts = [int(p) for p in s.lower().split("x")]
    return tuple(parts) if len(parts) == 3 else (parts[0],) * 3


def frame(nx, ny, nz):
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


def blas_in_maps(text):
    """The BLAS/LAPACK shared objects named in a /proc/<pid>/maps text."""
    libs = set()
    for line in text.splitlines():
        path = line.split()[-1] if line.split() else ""
        base = os.path.basename(path)
        if path.startswith("/") and ("blas" in base or "lapack" in base):
            libs.add(os.path.realpath(path) if os.path.exists(path) else path)
    return sorted(libs)


def global_symbol_library(name):
    import ctypes
    class DlInfo(ctypes.Structure):
        _fields_ = [("fname", ctypes.c_char_p), ("fbase", ctypes.c_void_p),
                    ("sname", ctypes.c_char_p), ("saddr", ctypes.c_void_p)]
    try:
        addr = ctypes.cast(getattr(ctypes.CDLL(None), name), ctypes.c_void_p).value
    except AttributeError:
        return "(not in the global scope: the wheel's own, loaded locally)"
    info = DlInfo()
    ctypes.CDLL(None).dladdr(ctypes.c_void_p(addr), ctypes.byref(info))
    return os.path.realpath(info.fname.decode())


def openblas_core():
    """The kernels of the OpenBLAS in this process's global scope (openblas_get_corename)."""
    import ctypes
    try:
        f = ctypes.CDLL(None).openblas_get_corename
    except AttributeError:
        return "(no OpenBLAS in the global scope)"
    f.restype = ctypes.c_char_p
    return f().decode()


def beamfea_core(exe):
    """The OpenBLAS kernels beamfea runs on, as `beamfea --version` says (it may replace OpenBLAS's
    own choice: app/openblas.hpp)."""
    out = subprocess.run([exe, "--version"], capture_output=True, text=True, check=True).stdout
    m = re.search(r"BLAS: OpenBLAS, (\S+) kernels", out)
    return m.group(1) if m else None


def run_beamfea(exe, model_path, probe):
    """Whole-process and analysis time of `beamfea run`, its roof ux, free DOFs and mapped BLAS."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "out")
        t0 = time.perf_counter()
        p = subprocess.Popen([exe, "run", model_path, "--out", out, "--no-vtk", "-q"])
        blas = []
        while p.poll() is None and not blas:  # the BLAS is mapped by the dynamic loader at start-up
            try:
                with open(f"/proc/{p.pid}/maps") as f:
                    text = f.read()
                if "cholmod" in text:
                    blas = blas_in_maps(text)
            except OSError:
                pass
            time.sleep(0.002)
        _, status, ru = os.wait4(p.pid, 0)
        total = time.perf_counter() - t0
        p.returncode = os.waitstatus_to_exitcode(status)
        if p.returncode != 0:
            raise RuntimeError(f"beamfea exited {p.returncode}")
        res = json.load(open(os.path.join(out, "results.json")))["analyses"]["lin"]
        return dict(process=total, process_cpu=ru.ru_utime + ru.ru_stime, analysis=res["wall_time_s"], ux=res["nodes"][str(probe)]["displacement"][0],
                    free_dofs=res["free_dofs"], blas=blas)


def opensees_child(nx, ny, nz, system, write_results):
    """Runs in the child process: builds the model in OpenSeesPy, times analyze + reactions; with
    write_results, then writes what beamfea's results.json holds that OpenSees computes (every
    node's displacement and reaction, every element's local end forces) as JSON to a temporary file."""
    import openseespy.opensees as ops
    nodes, elems, supports, loads = frame(nx, ny, nz)
    probe = nodes[-1][0]
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
    ops.system(system)
    ops.test("NormUnbalance", 1e-6, 1)
    ops.algorithm("Linear")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    t0 = time.perf_counter()
    ok = ops.analyze(1)
    ops.reactions()
    dt = time.perf_counter() - t0
    if write_results:
        with tempfile.TemporaryDirectory() as d, open(os.path.join(d, "results.json"), "w") as f:
            json.dump({"nodes": {str(n): {"displacement": ops.nodeDisp(n), "reaction": ops.nodeReaction(n)}
                                 for n, *_ in nodes},
                       "elements": {str(e + 1): {"end_forces": ops.eleResponse(e + 1, "localForce")}
                                    for e in range(len(elems))}}, f, indent=1)
    with open("/proc/self/maps") as f:
        blas = blas_in_maps(f.read())
    # Several BLAS may be mapped (the wheel's and the preloaded one): say which one dgemm_ binds to
    # in the global scope (the preloaded library comes first in the lookup order).
    blas.append("dgemm_ from " + global_symbol_library("dgemm_"))
    blas.append("kernels " + openblas_core())
    print(json.dumps(dict(ok=ok, analysis=dt, ux=ops.nodeDisp(probe, 1), blas=blas)))


def run_opensees(python, size, system, blas_lib, core, write_results):
    env = dict(os.environ)
    if blas_lib:
        env["LD_PRELOAD"] = blas_lib
    if core:
        env["OPENBLAS_CORETYPE"] = core
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run([python, os.path.abspath(__file__), "--opensees-child", "x".join(map(str, size)), system,
                        "1" if write_results else "0"],
                       env=env, capture_output=True, text=True)
    total = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    if r.returncode != 0:
        raise RuntimeError(f"OpenSees {system}: exit {r.returncode}: {r.stderr.strip()[-300:]}")
    d = json.loads(r.stdout.strip().splitlines()[-1])
    if d["ok"] != 0:
        raise RuntimeError(f"OpenSees {system} failed (analyze returned {d['ok']})")
    d["process"] = total
    d["process_cpu"] = cpu
    return d


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--beamfea", default="build/cli/beamfea")
    ap.add_argument("--python", default=sys.executable, help="interpreter with openseespy (>= 3.12 for OpenSeesPy 3.8)")
    ap.add_argument("--sizes", default="15x15x14", help="comma-separated n or nx x ny x nz bays")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--systems", default="Mumps,UmfPack")
    ap.add_argument("--blas", default=OPENBLAS, help="BLAS preloaded into OpenSees ('' keeps the wheel's own)")
    ap.add_argument("--openblas-core", default="beamfea",
                    help="OPENBLAS_CORETYPE for OpenSees: 'beamfea' (default) gives it the kernels beamfea runs on "
                         "(`beamfea --version`), '' lets its OpenBLAS choose, or a core name")
    ap.add_argument("--opensees-writes", action="store_true",
                    help="OpenSees also writes every node's displacement and reaction and every element's local "
                         "end forces to a JSON file (beamfea's results.json holds these and more), counted in its process")
    ap.add_argument("--opensees-child", nargs=3, metavar=("SIZE", "SYSTEM", "WRITE"), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.opensees_child:
        opensees_child(*parse_size(a.opensees_child[0]), a.opensees_child[1], a.opensees_child[2] == "1")
        return
    systems = a.systems.split(",")
    core = beamfea_core(a.beamfea) if a.openblas_core == "beamfea" else a.openblas_core
    print(f"beamfea: {a.beamfea} ({subprocess.run([a.beamfea, '--version'], capture_output=True, text=True).stdout.strip()})")
    print(f"OpenSees: OPENBLAS_CORETYPE={core or '(unset)'}" + (f", LD_PRELOAD={a.blas}" if a.blas else "") + "\n")
    head = ["bays", "free DOFs", "beamfea process s (CPU s)", "beamfea analysis s"]
    for s in systems:
        head += [f"OpenSees {s} process s (CPU s)", f"OpenSees {s} analysis s",
                 f"{s}/beamfea process (CPU)", f"{s}/beamfea analysis"]
    print("| " + " | ".join(head) + " |")
    print("|---" + "|---:" * (len(head) - 1) + "|", flush=True)
    blas_seen = {}
    for spec in a.sizes.split(","):
        size = parse_size(spec)
        nodes, elems, supports, loads = frame(*size)
        probe = nodes[-1][0]
        with tempfile.TemporaryDirectory() as d:
            model_path = os.path.join(d, "m.json")
            with open(model_path, "w") as f:
                json.dump(beamfea_model(nodes, elems, supports, loads), f)
            sides = ["beamfea"] + systems
            runs = {s: [] for s in sides}
            for rep in range(a.repeat):
                order = sides[rep % len(sides):] + sides[:rep % len(sides)]
                for s in order:
                    r = run_beamfea(a.beamfea, model_path, probe) if s == "beamfea" else \
                        run_opensees(a.python, size, s, a.blas, core, a.opensees_writes)
                    runs[s].append(r)
                    blas_seen.setdefault(s, set()).update(r["blas"])
        bf = runs["beamfea"]
        for s in systems:
            for r, b in zip(runs[s], bf):
                if abs(r["ux"] - b["ux"]) > 1e-6 * abs(b["ux"]):
                    raise RuntimeError(f"answers differ ({s}): {r['ux']} vs {b['ux']}")
        med = lambda s, k: statistics.median(r[k] for r in runs[s])
        row = ["x".join(map(str, size)), f"{bf[0]['free_dofs']:,}",
               f"{med('beamfea', 'process'):.3g} ({med('beamfea', 'process_cpu'):.3g})", f"{med('beamfea', 'analysis'):.3g}"]
        for s in systems:
            ratio = lambda k: statistics.median(r[k] / b[k] for r, b in zip(runs[s], bf))
            row += [f"{med(s, 'process'):.3g} ({med(s, 'process_cpu'):.3g})", f"{med(s, 'analysis'):.3g}",
                    f"{ratio('process'):.2f} ({ratio('process_cpu'):.2f})", f"{ratio('analysis'):.2f}"]
        print("| " + " | ".join(row) + " |", flush=True)
        for s in sides:
            print(f"<!-- {spec} {s} process: " + ", ".join(f"{r['process']:.3f}" for r in runs[s]) +
                  "; process CPU: " + ", ".join(f"{r['process_cpu']:.3f}" for r in runs[s]) +
                  "; analysis: " + ", ".join(f"{r['analysis']:.3f}" for r in runs[s]) + " -->", flush=True)
    print()
    for s, libs in blas_seen.items():
        print(f"BLAS mapped by {s}: {', '.join(sorted(libs)) or 'none found'}")
    print(f"load average at the end: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
