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
        if "stiffness" in j:
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


def bennett(theta0_deg=100.0, turn_deg=150.0, increments=30):
    """Bennett's linkage (Bennett 1903): Denavit-Hartenberg frames T_{i+1} = T_i Rz(theta_i) Tx(a_i)
    Rx(alpha_i), links a, b, a, b of twists 60 and 90 degrees (a sin(beta) = b sin(alpha)), closed for
    theta_3 = 2 pi - theta_1, theta_4 = 2 pi - theta_2, tan(theta_1/2) tan(theta_2/2) =
    sin((beta + alpha)/2) / sin((beta - alpha)/2). Ground link 4 fixed, a spring k at joint 1 and the
    moment k about its axis: theta_1 = theta_0 + lambda exactly (the passive joints carry nothing)."""
    al, be, a = np.radians(60.0), np.radians(90.0), 1.0
    b = a * np.sin(be) / np.sin(al)
    K = np.sin((be + al) / 2) / np.sin((be - al) / 2)

    def frames(t1):
        t2 = 2 * np.arctan(K / np.tan(t1 / 2))
        T, out = np.eye(4), [np.eye(4)]
        for th, ln, tw in zip((t1, t2, 2 * np.pi - t1, 2 * np.pi - t2), (a, b, a, b), (al, be, al, be)):
            c, s, ct, st = np.cos(th), np.sin(th), np.cos(tw), np.sin(tw)
            T = T @ np.array([[c, -s * ct, s * st, ln * c], [s, c * ct, -c * st, ln * s], [0, st, ct, 0], [0, 0, 0, 1]])
            out.append(T)
        assert np.abs(out[4] - np.eye(4)).max() < 1e-12
        return out

    F = frames(np.radians(theta0_deg))
    P = [f[:3, 3].tolist() for f in F[:4]]
    Z = [f[:3, 2].tolist() for f in F[:4]]
    nodes = [{"id": i, "xyz": P[j]} for i, j in (("J1g", 0), ("J1l", 0), ("J2a", 1), ("J2b", 1), ("J3a", 2),
                                                 ("J3b", 2), ("J4a", 3), ("J4g", 3))]
    k = 10.0
    joints = [{"id": f"j{i + 1}", "type": "revolute", "nodes": n, "axes": [Z[i]]}
              for i, n in enumerate((["J1g", "J1l"], ["J2a", "J2b"], ["J3a", "J3b"], ["J4a", "J4g"]))]
    joints[0]["stiffness"] = [k]
    doc = {"nodes": nodes,
           "elements": [{"id": "l1", "type": "rigid", "nodes": ["J1l", "J2a"]},
                        {"id": "l2", "type": "rigid", "nodes": ["J2b", "J3a"]},
                        {"id": "l3", "type": "rigid", "nodes": ["J3b", "J4a"]}],
           "joints": joints, "supports": [{"node": "J1g", "fix": "all"}, {"node": "J4g", "fix": "all"}],
           "loads": [{"node": "J1l", "force": [0.0, 0.0, 0.0], "moment": [k * z for z in Z[0]]}],
           "analyses": [{"id": "path", "type": "path", "track": ["J3a"],
                         "control": {"load_factor": float(np.radians(turn_deg)), "increments": increments}}]}
    return doc, lambda lam: frames(np.radians(theta0_deg) + lam)[2][:3, 3]


def test_a_bennett_linkage_chooses_its_redundant_rows_afresh_and_stays_closed_in_any_units():
    doc, joint3 = bennett()
    mm = scaled(doc)
    for load in mm["loads"]:
        load["moment"] = [A_LEN * B_FORCE * m for m in load["moment"]]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        runs = [beamfea.run(d)["analyses"]["path"] for d in (doc, mm)]
    msgs = [str(w.message) for w in caught if issubclass(w.category, beamfea.BeamfeaWarning)]
    assert sum("redundant constraint rows were chosen afresh along the path" in m for m in msgs) == 2, msgs
    for r, a in zip(runs, (1.0, A_LEN)):
        assert r["completed"] is True, r["termination"]
        assert not [c for c in r["critical_points"] if c["type"] == "singularity"]
        changed = [s for s in r["steps"] if "statically_indeterminate" in s]
        assert len(changed) >= 1
        # Chosen afresh before the rows kept at the reference (its three rotation rows, dependent at
        # theta_1 = 180 degrees where the four axes are coplanar) lose rank: 80 degrees of turn.
        assert changed[0]["load_factor"] < np.radians(80.0)
        assert changed[0]["statically_indeterminate"] != r["statically_indeterminate"]
        assert len(changed[0]["statically_indeterminate"]) == 3
        P0 = joint3(0.0)
        for s in r["steps"]:
            u = np.array(s["nodes"]["J3a"]["displacement"][:3]) / a
            assert np.linalg.norm(P0 + u - joint3(s["load_factor"])) < 1e-7
    si, mm = runs
    assert [s["step"] for s in si["steps"] if "statically_indeterminate" in s] == \
           [s["step"] for s in mm["steps"] if "statically_indeterminate" in s]
