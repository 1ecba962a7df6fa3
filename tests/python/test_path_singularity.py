"""Singular poses of closed loops along a path, seen from Python: a "singularity" critical point with
the loop's passive joints and nodes, the path's termination naming it, the same in two unit systems,
and the warning for a singular pose the path passed."""
import copy
import os
import sys
import warnings

import numpy as np
import pytest

import beamfea
from conftest import SOURCE_DIR

A_LEN, B_FORCE = 1e3, 1e-3  # mm and kN against m and N, say: lengths x a, forces x b


def bu_lumped_loaded():
    """examples/02's lumped 3-RRR (Bu 2012) at P1 with a force (0, -1) on the platform, load control."""
    sys.path.insert(0, os.path.join(SOURCE_DIR, "docs", "notes"))
    try:
        from bu_mechanism import JOINTS, ik
    finally:
        sys.path.pop(0)
    pts = ik(1.1)
    xyz = lambda p: [float(p[0]), float(p[1]), 0.0]
    nodes, joints = [], []
    for j in JOINTS:
        nodes += [{"id": j + "a", "xyz": xyz(pts[j])}, {"id": j + "b", "xyz": xyz(pts[j])}]
        joints.append({"id": j, "type": "revolute", "nodes": [j + "a", j + "b"], "axes": [[0, 0, 1]],
                       "stiffness": [1.0 if j in ("J1", "J2", "J3") else 0.0]})
    nodes.append({"id": "P", "xyz": xyz(pts["P"])})
    links = [("J1J2", "J1b", "J2a"), ("J2J3", "J2b", "J3a"), ("J3P", "J3b", "P"), ("PJ4", "P", "J4a"),
             ("J4J5", "J4b", "J5a"), ("J5J6", "J5b", "J6a")]
    return {"nodes": nodes, "elements": [{"id": i, "type": "rigid", "nodes": [a, b]} for i, a, b in links],
            "joints": joints, "supports": [{"node": "J1a", "fix": "all"}, {"node": "J6b", "fix": "all"}],
            "loads": [{"node": "P", "force": [0.0, -1.0, 0.0]}],
            "analyses": [{"id": "path", "type": "path", "track": ["P"],
                          "control": {"load_factor": 1.0, "increments": 20}}]}


def scaled(doc, a=A_LEN, b=B_FORCE):
    d = copy.deepcopy(doc)
    for n in d["nodes"]:
        n["xyz"] = [a * x for x in n["xyz"]]
    for j in d["joints"]:
        j["stiffness"] = [a * b * k for k in j["stiffness"]]  # moment per radian
    for load in d["loads"]:
        load["force"] = [b * f for f in load["force"]]
    return d


def test_bu_path_ends_at_the_singular_pose_of_its_passive_dyad_in_any_units():
    runs = [beamfea.run(m)["analyses"]["path"] for m in (bu_lumped_loaded(), scaled(bu_lumped_loaded()))]
    for r in runs:
        assert r["completed"] is False
        assert r["termination"].startswith("singular pose at load factor 0.2183")
        assert "no convergence" not in r["termination"]
        c = r["critical_points"][-1]
        assert c["type"] == "singularity"
        assert c["joints"] == ["J4", "J5", "J6"]
        assert c["nodes"] == ["J4a", "J4b", "J5a", "J5b", "J6a", "J6b"]
        assert c["passed"] is False
        assert c["control"] == c["load_factor"]
    si, mm = runs
    assert mm["critical_points"][-1]["load_factor"] == pytest.approx(si["critical_points"][-1]["load_factor"], rel=1e-9)
    assert len(mm["steps"]) == len(si["steps"])


def change_point_four_bar():
    """A four-bar at its change point (crank 0.3 + ground 0.7 = coupler 0.5 + rocker 0.5) driven by a
    prescribed crank rotation from 2.6 rad through pi, where coupler and rocker line up."""
    a, g, b, c, th = 0.3, 0.7, 0.5, 0.5, 2.6
    B = np.array([a * np.cos(th), a * np.sin(th)])
    D = np.array([g, 0.0])
    d = np.linalg.norm(D - B)  # C: the circles |C - D| = c, |C - B| = b, left of D -> B
    e = (B - D) / d
    x = (c * c - b * b + d * d) / (2 * d)
    C = D + x * e + np.sqrt(c * c - x * x) * np.array([-e[1], e[0]])
    pts = {"A": [0.0, 0.0], "B": B, "C": C, "D": D}
    nodes = []
    for k, p in pts.items():
        nodes += [{"id": k, "xyz": [float(p[0]), float(p[1]), 0.0]}, {"id": k + "1", "xyz": [float(p[0]), float(p[1]), 0.0]}]
    z = [[0, 0, 1]]
    return {"nodes": nodes,
            "elements": [{"id": "crank", "type": "rigid", "nodes": ["A1", "B"]},
                         {"id": "coupler", "type": "rigid", "nodes": ["B1", "C"]},
                         {"id": "rocker", "type": "rigid", "nodes": ["D1", "C1"]}],
            "joints": [{"id": "jA", "type": "revolute", "nodes": ["A", "A1"], "axes": z, "stiffness": [5.0]},
                       {"id": "jB", "type": "revolute", "nodes": ["B", "B1"], "axes": z},
                       {"id": "jC", "type": "revolute", "nodes": ["C", "C1"], "axes": z},
                       {"id": "jD", "type": "revolute", "nodes": ["D", "D1"], "axes": z}],
            "supports": [{"node": "A", "fix": "all"}, {"node": "D", "fix": "all"}],
            "analyses": [{"id": "drive", "type": "path", "track": ["C"],
                          "control": {"node": "A1", "dof": "rz", "to": 1.0, "increments": 10}}]}


def test_a_passed_singular_pose_is_reported_and_warned():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = beamfea.run(change_point_four_bar())["analyses"]["drive"]
    assert r["completed"] is True
    sing = [c for c in r["critical_points"] if c["type"] == "singularity"]
    assert len(sing) == 1
    assert sorted(sing[0]["joints"]) == ["jB", "jC", "jD"]
    assert sing[0]["passed"] is True
    assert sing[0]["control"] == pytest.approx(np.pi - 2.6, abs=1e-4)
    msgs = [str(w.message) for w in caught if issubclass(w.category, beamfea.BeamfeaWarning)]
    assert any("passed a singular pose" in m and "'jB'" in m for m in msgs), msgs
