"""Poses from Python: beamfea.run returns the posed geometry, a bad pose raises naming its joint or
node, and a sweep over /pose values reports an unreachable pose as its row (docs/poses.md)."""
import math

import numpy as np
import pytest

import beamfea

L1, L2 = 0.4, 0.3


def arm(q1=0.0, q2=0.0):
    """A planar two-link arm (links along x in the reference), posed by its joint angles."""
    return {
        "nodes": [{"id": "G", "xyz": [0, 0, 0]}, {"id": "A", "xyz": [0, 0, 0]}, {"id": "E1", "xyz": [L1, 0, 0]},
                  {"id": "E2", "xyz": [L1, 0, 0]}, {"id": "T", "xyz": [L1 + L2, 0, 0]}],
        "materials": [{"id": "al", "E": 7e10, "nu": 0.33}],
        "sections": [{"id": "s", "shape": "rectangle", "b": 0.02, "h": 0.04}],
        "elements": [{"id": "l1", "type": "beam", "nodes": ["A", "E1"], "material": "al", "section": "s"},
                     {"id": "l2", "type": "beam", "nodes": ["E2", "T"], "material": "al", "section": "s"}],
        "joints": [{"id": "q1", "type": "revolute", "nodes": ["G", "A"], "axes": [[0, 0, 1]], "stiffness": [2000]},
                   {"id": "q2", "type": "revolute", "nodes": ["E1", "E2"], "axes": [[0, 0, 1]], "stiffness": [1000],
                    "limits": [[-2.5, 2.5]]}],
        "supports": [{"node": "G", "fix": "all"}],
        "pose": {"joints": {"q1": q1, "q2": q2}},
        "analyses": [{"id": "K", "type": "stiffness", "node": "T"}],
    }


def tip(q1, q2):
    return [L1 * math.cos(q1) + L2 * math.cos(q1 + q2), L1 * math.sin(q1) + L2 * math.sin(q1 + q2), 0.0]


def test_run_returns_the_pose():
    res = beamfea.run(arm(0.4, -0.9))
    assert res["pose"]["joints"] == {"q1": 0.4, "q2": -0.9}
    assert np.allclose(res["pose"]["nodes"]["T"], tip(0.4, -0.9), atol=1e-14)
    assert res["analyses"]["K"]["status"] == "ok"


def test_a_pose_beyond_a_limit_raises_naming_the_joint():
    with pytest.raises(beamfea.InputError, match=r"/pose/joints/q2.*outside its limits \[-2.5, 2.5\]"):
        beamfea.run(arm(0.0, 3.0))


def test_a_pose_sweep_reports_the_unreachable_case_as_its_row():
    spec = {"model": arm(), "grid": [{"name": "q2", "pointer": "/pose/joints/q2", "values": [-1.0, 3.0, 1.0]}],
            "outputs": [{"name": "tip", "path": "pose.nodes.T"}]}
    cols = beamfea._beamfea.sweep(spec, 0, None)
    assert cols["status"] == ["ok", "bad input", "ok"]
    assert "joint 'q2'" in cols["message"][1] and "limits" in cols["message"][1]
    assert np.allclose([cols["tip[0]"][0], cols["tip[1]"][0]], tip(0.0, -1.0)[:2], atol=1e-14)
    assert np.allclose([cols["tip[0]"][2], cols["tip[1]"][2]], tip(0.0, 1.0)[:2], atol=1e-14)
    assert np.isnan(cols["tip[0]"][1])


def bent_arm(beta0=0.5):
    """The arm with its elbow bent by beta0 in the reference, driven by a target of its tip T."""
    doc = arm()
    t = [L1 + L2 * math.cos(beta0), L2 * math.sin(beta0), 0.0]
    doc["nodes"][4]["xyz"] = t
    doc["pose"] = {"nodes": [{"node": "T", "xyz": t}]}
    return doc


def test_a_sweep_over_a_target_solves_the_inverse_kinematics_of_the_reference_branch():
    # Closed form: the elbow angle by the law of cosines, positive as in the reference (beta0 > 0);
    # then the shoulder. x = 1.0 is beyond the arm's reach (L1 + L2 = 0.7).
    xs = [0.45, 0.3, 1.0, 0.2]
    y, beta0 = 0.35, 0.5
    base = bent_arm(beta0)
    base["pose"]["nodes"][0]["xyz"] = [xs[0], y, 0.0]
    spec = {"model": base, "grid": [{"name": "x", "pointer": "/pose/nodes/0/xyz/0", "values": xs}],
            "outputs": [{"name": "q1", "path": "pose.joints.q1"}, {"name": "q2", "path": "pose.joints.q2"}]}
    cols = beamfea._beamfea.sweep(spec, 0, None)
    assert cols["status"] == ["ok", "ok", "bad input", "ok"]
    assert "node 'T'" in cols["message"][2] and "beyond reach" in cols["message"][2]
    for n, x in enumerate(xs):
        if n == 2:
            continue
        elbow = math.acos((x * x + y * y - L1 * L1 - L2 * L2) / (2 * L1 * L2))
        shoulder = math.atan2(y, x) - math.atan2(L2 * math.sin(elbow), L1 + L2 * math.cos(elbow))
        assert cols["q2"][n] == pytest.approx(elbow - beta0, abs=1e-10)
        assert cols["q1"][n] == pytest.approx(shoulder, abs=1e-10)
