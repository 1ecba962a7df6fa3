#!/usr/bin/env python3
"""Writes the seed corpus of the model fuzzer (tests/fuzz/corpus/): small models from the
examples and tests, one per analysis type, and the mutations that found bugs (issue 9).
Files are small JSON (or deliberately broken) texts; the replay test runs each through
`beamfea check` and `beamfea run` (tests/fuzz/corpus_replay_test.cpp).
Run from the repository root: python3 tests/fuzz/make_corpus.py"""
import copy
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "corpus")
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


def write(name, doc):
    text = doc if isinstance(doc, str) else json.dumps(doc, separators=(",", ":"))
    with open(os.path.join(OUT, name), "w") as f:
        f.write(text)


def example(path, bound_steps=None):
    with open(os.path.join(ROOT, path)) as f:
        d = json.load(f)
    if bound_steps:
        for a in d.get("analyses", []):
            if a.get("type") == "path":
                a["max_steps"] = bound_steps
    return d


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
    shapes = cantilever()
    shapes["sections"] = [{"id": "s", "shape": "tube", "d": 0.05, "t": 0.004}]
    write("seed_shape_tube.json", shapes)

    # Mutations that found bugs (issue 9), one per class.
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


if __name__ == "__main__":
    main()
