#!/usr/bin/env python3
"""Writes the seed corpora of the fuzzers (docs/testing.md):
- tests/fuzz/corpus/ for fuzz_model: small models from the examples and tests, one per analysis
  type, and the mutations that found bugs;
- tests/fuzz/corpus_sweep/ for fuzz_sweep: sweep files (grid, list, patches, a base file, an
  analysis subset, failing cases) and the sweep files that found bugs, with base.json, the one
  base model file the sweeps name (the fuzzer reads no other file).
Files are small JSON (or deliberately broken) texts; the replay tests run each through
`beamfea check` and `beamfea run`, or `beamfea sweep` (tests/fuzz/corpus_replay_test.cpp).
Run from the repository root: python3 tests/fuzz/make_corpus.py"""
import copy
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "corpus")
OUT_SWEEP = os.path.join(HERE, "corpus_sweep")
ROOT = os.path.dirname(os.path.dirname(HERE))


def cantilever(**kw):
    d = {
        "nodes": [{"id": "A", "xyz": [0, 0, 0]}, {"id": "B", "xyz": [2, 0, 0]}],
        "materials": [{"id": "m", "E": 2.1e11, "G": 8.1e10}],
        "sections": [{"id": "s", "A": 1e-3, "Iy": 2e-6, "Iz": 3e-6, "J": 1e-6}],
        "elements": [{"id": "e", "type": "beam", "nodes": ["A", "B"], "material": "m", "section": "s",
                      "orientation": [0, 0, 1], "divisions": 2}],
        "supports": [{"node": "A", "fix": "all"}],
        "loads": [{"node": "B", "force": [-1000, -100, 0]}],
        "analyses": [{"id": "lin", "type": "linear_static"}],
    }
    d.update(kw)
    return d


def write(name, doc, folder=OUT):
    text = doc if isinstance(doc, str) else json.dumps(doc, separators=(",", ":"))
    with open(os.path.join(folder, name), "w") as f:
        f.write(text)


def write_sweep(name, doc):
    write(name, doc, OUT_SWEEP)


def example(path, bound_steps=None):
    with open(os.path.join(ROOT, path)) as f:
        d = json.load(f)
    if bound_steps:
        for a in d.get("analyses", []):
            if a.get("type") == "path":
                a["max_steps"] = bound_steps
    return d


def bennett(turn_deg=150.0, increments=10):
    """Bennett's linkage (four revolute joints in a spatial loop; links 1, 1.155, twists 60 and 90
    degrees), built at 100 degrees of joint 1 and turned by a moment: the path chooses its redundant
    closure rows afresh twice (docs/analyses/path.md)."""
    import math
    al, be, a = math.radians(60.0), math.radians(90.0), 1.0
    b = a * math.sin(be) / math.sin(al)
    K = math.sin((be + al) / 2) / math.sin((be - al) / 2)
    t1 = math.radians(100.0)
    t2 = 2 * math.atan(K / math.tan(t1 / 2))
    T = [[float(i == j) for j in range(4)] for i in range(4)]
    frames = [T]
    for th, ln, tw in zip((t1, t2, 2 * math.pi - t1, 2 * math.pi - t2), (a, b, a, b), (al, be, al, be)):
        c, s, ct, st = math.cos(th), math.sin(th), math.cos(tw), math.sin(tw)
        M = [[c, -s * ct, s * st, ln * c], [s, c * ct, -c * st, ln * s], [0, st, ct, 0], [0, 0, 0, 1]]
        T = [[sum(T[i][k] * M[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
        frames.append(T)
    P = [[round(f[i][3], 12) for i in range(3)] for f in frames[:4]]
    Z = [[round(f[i][2], 12) for i in range(3)] for f in frames[:4]]
    nodes = [{"id": i, "xyz": P[j]} for i, j in (("J1g", 0), ("J1l", 0), ("J2a", 1), ("J2b", 1), ("J3a", 2),
                                                 ("J3b", 2), ("J4a", 3), ("J4g", 3))]
    joints = [{"id": f"j{i + 1}", "type": "revolute", "nodes": n, "axes": [Z[i]]}
              for i, n in enumerate((["J1g", "J1l"], ["J2a", "J2b"], ["J3a", "J3b"], ["J4a", "J4g"]))]
    joints[0]["stiffness"] = [10.0]
    return {"nodes": nodes,
            "elements": [{"id": "l1", "type": "rigid", "nodes": ["J1l", "J2a"]},
                         {"id": "l2", "type": "rigid", "nodes": ["J2b", "J3a"]},
                         {"id": "l3", "type": "rigid", "nodes": ["J3b", "J4a"]}],
            "joints": joints, "supports": [{"node": "J1g", "fix": "all"}, {"node": "J4g", "fix": "all"}],
            "loads": [{"node": "J1l", "moment": [10.0 * z for z in Z[0]]}],
            "analyses": [{"id": "p", "type": "path", "track": ["J3a"],
                          "control": {"load_factor": round(math.radians(turn_deg), 12), "increments": increments}}]}


def main():
    os.makedirs(OUT, exist_ok=True)
    # Seeds: the examples (paths bounded to a few steps) and one model per analysis type.
    write("seed_example01.json", example("examples/01_space_frame/model.json"))
    write("seed_example03.json", example("examples/03_workspace_stiffness_map/model.json"))
    write("seed_example04.json", example("examples/04_load_sweep/model.json"))
    write("seed_example05_A_Pi_lumped.json", example("examples/05_pashkevich_chain/models/A_Pi_lumped.json"))
    write("seed_example06_lee.json", example("examples/06_lees_frame/model.json", bound_steps=8))
    write("seed_linear.json", cantilever())
    write("seed_stiffness.json", cantilever(analyses=[{"id": "K", "type": "stiffness", "node": "B"}]))
    write("seed_buckling.json", cantilever(analyses=[{"id": "b", "type": "buckling", "modes": 2}]))
    write("seed_path_load.json", cantilever(analyses=[{"id": "p", "type": "path", "control": {"load_factor": 1.0, "increments": 3}}]))
    write("seed_path_disp.json", cantilever(analyses=[{"id": "p", "type": "path",
                                                      "control": {"node": "B", "dof": "uy", "to": -0.01, "increments": 3}}]))
    write("seed_path_arc.json", cantilever(analyses=[{"id": "p", "type": "path", "control": {"arc_length": 0.05},
                                                     "stop": {"steps": 4}, "track": ["B"], "stiffness_node": "B"}]))
    hinge = cantilever()
    hinge["nodes"] += [{"id": "C", "xyz": [2, 0, 0]}, {"id": "D", "xyz": [3, 0, 0]}]
    hinge["elements"].append({"id": "r", "type": "rigid", "nodes": ["C", "D"]})
    hinge["joints"] = [{"id": "j", "type": "revolute", "nodes": ["B", "C"], "axes": [[0, 0, 1]], "stiffness": [50.0]}]
    hinge["loads"] = [{"node": "D", "force": [0, -10, 0]}, {"joint": "j", "coordinate": 0, "value": 1.0}]
    write("seed_joint_rigid.json", hinge)
    write("seed_bennett_rows_rechosen.json", bennett())
    shapes = cantilever()
    shapes["sections"] = [{"id": "s", "shape": "tube", "d": 0.05, "t": 0.004}]
    write("seed_shape_tube.json", shapes)

    # Mutations that found bugs, one per class.
    held = cantilever()
    held["supports"].append({"node": "B", "fix": "all"})
    for kind, spec in [("buckling", {"id": "b", "type": "buckling"}),
                       ("path", {"id": "p", "type": "path", "control": {"load_factor": 1.0, "increments": 2}})]:
        d = copy.deepcopy(held)
        d["analyses"] = [spec]
        write(f"bug_zero_free_dofs_{kind}.json", d)  # SIGSEGV before
    write("bug_id_dotdot.json", cantilever(analyses=[{"id": "../x", "type": "linear_static"}]))
    write("bug_id_slash.json", cantilever(analyses=[{"id": "a/b", "type": "linear_static"}]))
    write("bug_id_long.json", cantilever(analyses=[{"id": "a" * 300, "type": "linear_static"}]))
    write("bug_stiffness_at_support.json", cantilever(analyses=[{"id": "lin", "type": "linear_static"},
                                                               {"id": "K", "type": "stiffness", "node": "A"}]))
    write("bug_control_on_support.json", cantilever(analyses=[{"id": "p", "type": "path",
                                                               "control": {"node": "A", "dof": "ux", "to": 0.1}}]))
    write("bug_support_vs_prescribed.json", cantilever(prescribed=[{"node": "A", "dof": "uy", "value": 0.01}]))
    write("bug_prescribed_twice.json", cantilever(prescribed=[{"node": "B", "dof": "uy", "value": 0.01},
                                                              {"node": "B", "dof": "uy", "value": 0.02}]))
    write("bug_imperfection_mode.json", cantilever(analyses=[{"id": "p", "type": "path", "control": {"arc_length": 0.01},
                                                              "imperfection": {"mode": 99, "amplitude": 0.001}}]))
    write("bug_path_no_loads.json", cantilever(loads=[], analyses=[{"id": "p", "type": "path",
                                                                    "control": {"load_factor": 1.0}}]))
    d = cantilever()
    d["elements"][0]["divisions"] = 4294967297
    write("bug_divisions_wrap.json", d)
    d = cantilever()
    d["elements"][0]["divisions"] = 1000000
    write("bug_divisions_huge.json", d)
    d = cantilever()
    d["gravity"] = [0, 0, -9.81]
    write("bug_unknown_key.json", d)
    d = cantilever()
    del d["analyses"]
    write("bug_no_analyses.json", d)
    write("bug_force_1e308.json", cantilever(loads=[{"node": "B", "force": [0, -1e308, 0]}]))
    write("bug_number_1e999.json", json.dumps(cantilever()).replace("[2, 0, 0]", "[1e999, 0, 0]"))
    d = cantilever()
    d["nodes"][1]["xyz"] = [1e308, 0, 0]
    write("bug_coordinates_1e308.json", d)
    write("bug_nonfinite_result.json", cantilever(
        nodes=[{"id": "A", "xyz": [0, 0, 0]}, {"id": "B", "xyz": [1e-50, 0, 0]}],
        materials=[{"id": "m", "E": 1e100, "G": 1e100}],
        sections=[{"id": "s", "A": 1e100, "Iy": 1e100, "Iz": 1e100, "J": 1e100}]))
    write("bug_deep_nesting.json", '{"_x": ' + "[" * 2000 + "]" * 2000 + "}")
    rig = cantilever()
    rig["nodes"].append({"id": "C", "xyz": [0, 1, 0]})
    rig["elements"].append({"id": "r", "type": "rigid", "nodes": ["A", "C"]})
    d = copy.deepcopy(rig)
    d["analyses"] = [{"id": "K", "type": "stiffness", "node": "C"}]
    write("bug_stiffness_held_by_rigid_link.json", d)
    d = copy.deepcopy(rig)
    d["prescribed"] = [{"node": "C", "dof": "uz", "value": 0.01}]
    write("bug_rigid_body_disagree.json", d)
    write("bug_no_elements.json", cantilever(elements=[]))
    write("bug_malformed.json", '{"nodes": [}')
    write("bug_not_an_object.json", "[1, 2, 3]")
    write("bug_empty.json", "")


def sweeps():
    os.makedirs(OUT_SWEEP, exist_ok=True)
    base = cantilever(analyses=[{"id": "lin", "type": "linear_static"}, {"id": "K", "type": "stiffness", "node": "B"}])
    write_sweep("base.json", base)
    tip = "analyses.lin.nodes.B.displacement[1]"
    # Seeds: every form of the sweep file.
    write_sweep("seed_grid_base.json", {
        "base": "base.json",
        "grid": [{"name": "P", "pointer": "/loads/0/force/1", "values": [-100, -200, 50.5]},
                 {"name": "L", "pointer": "/nodes/1/xyz/0", "values": [1.0, 2.5]}],
        "outputs": [tip, {"name": "K", "path": "analyses.K.matrix"}]})
    write_sweep("seed_grid_inline.json", {
        "model": base,
        "grid": [{"name": "b", "pointer": ["/sections/0/Iy", "/sections/0/Iz"], "values": [1e-6, 2e-6]}],
        "outputs": ["/analyses/lin/nodes/B/displacement/1", "analyses.K.rank"]})
    write_sweep("seed_grid_patches.json", {
        "base": "base.json",
        "grid": [{"name": "extra", "values": ["none", "second load"],
                  "patches": [[], [{"op": "add", "path": "/loads/-", "value": {"node": "B", "force": [0, 0, -10]}}]]}],
        "outputs": [tip]})
    write_sweep("seed_list_set_patch.json", {
        "base": "base.json",
        "cases": [{"id": "soft", "parameters": {"E": 7e10}, "set": {"/materials/0/E": 7e10}},
                  {"id": "both", "set": {"/loads/0/force/1": -5.0},
                   "patch": [{"op": "replace", "path": "/sections/0/Iz", "value": 4e-6}]},
                  {}],
        "outputs": [tip]})
    write_sweep("seed_analyses_subset.json", {
        "base": "base.json", "analyses": ["K"],
        "cases": [{"id": "a"}, {"id": "b", "set": {"/nodes/1/xyz/0": 3.0}}],
        "outputs": ["analyses.K.matrix[1][1]"], "description": "only the stiffness"})
    # One case a mechanism (no support: analysis failed), one bad input (unknown section): exit 1.
    write_sweep("seed_failing_cases.json", {
        "base": "base.json",
        "cases": [{"id": "ok"}, {"id": "free", "patch": [{"op": "remove", "path": "/supports/0"}]},
                  {"id": "bad", "set": {"/elements/0/section": "nope"}}],
        "outputs": [tip]})
    write_sweep("seed_path.json", {
        "model": cantilever(analyses=[{"id": "p", "type": "path", "control": {"load_factor": 1.0, "increments": 2}}]),
        "grid": [{"name": "P", "pointer": "/loads/0/force/0", "values": [-10, -20]}],
        "outputs": ["analyses.p.steps"]})
    # Found by fuzz_sweep: a whole analysis as outputs gives its wall_time_s column, which a resumed
    # loop's re-run case fills with another time (the harness compared it; now it sets every time aside).
    write_sweep("bug_analysis_wall_time_column.json", {
        "base": "base.json",
        "grid": [{"name": "extra", "values": ["none", "second load"],
                  "patches": [[], [{"op": "add", "path": "/loads/-", "value": {"nodJJ": "B", "force": [1, 0, -10]}}]]}],
        "outputs": ["analyses.lin"]})
    write_sweep("bad_unknown_key.json", {"base": "base.json", "grid": [{"pointer": "/loads/0/force/1", "values": [1]}],
                                         "output": [tip]})
    write_sweep("bad_pointer_missing.json", {"base": "base.json",
                                             "grid": [{"pointer": "/loads/0/force/7", "values": [1, 2]}]})


if __name__ == "__main__":
    main()
    sweeps()
