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
    cols = beamfea._beamfea.sweep(spec, 0)
    assert cols["status"] == ["ok", "bad input", "ok"]
    assert "joint 'q2'" in cols["message"][1] and "limits" in cols["message"][1]
    assert np.allclose([cols["tip[0]"][0], cols["tip[1]"][0]], tip(0.0, -1.0)[:2], atol=1e-14)
    assert np.allclose([cols["tip[0]"][2], cols["tip[1]"][2]], tip(0.0, 1.0)[:2], atol=1e-14)
    assert np.isnan(cols["tip[0]"][1])
