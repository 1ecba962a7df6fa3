"""actuator_allocation on a posed lumped model: W. Bu (2012)'s manipulator as a lumped (VJM) model
(rigid links, six revolute joints), one reference geometry (P1), posed by a `pose.nodes` target on the
platform at P1..P5. With rigid links the frozen structure holds the platform rigidly (C_S = 0, not a
mechanism), so every scheme's total stiffness is its actuated one, K_A = J^-T K_I J^-1 (eq. 10), with
J of the paper's eqs. 21-25 at the posed geometry (docs/notes/bu_mechanism.py: the closed-form inverse
kinematics and screw columns, independent of the engine)."""
import importlib.util
import os

import numpy as np
import pytest

import beamfea
from conftest import SOURCE_DIR

_spec = importlib.util.spec_from_file_location("bu_mechanism", os.path.join(SOURCE_DIR, "docs", "notes", "bu_mechanism.py"))
mech = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(mech)

K_ACT = 3.0
TOL = 1e-9  # relative: rigid links, both sides exact
JOINT_NODES = {"J1": ("J1g", "J1l"), "J2": ("J2p", "J2d"), "J3": ("J3p", "J3d"),
               "J6": ("J6g", "J6l"), "J5": ("J5p", "J5d"), "J4": ("J4p", "J4d")}
LINKS = [("J1J2", "J1l", "J2p"), ("J2J3", "J2d", "J3p"), ("J3P", "J3d", "P"), ("PJ4", "P", "J4d"),
         ("J4J5", "J4p", "J5d"), ("J5J6", "J5p", "J6l")]
SCHEMES = [["J1", "J2", "J3"], ["J1", "J2", "J6"]]
DIRS = ["rz", "ux", "uy"]  # the paper's [phi, x, y]


def bu_lumped(y):
    """Reference geometry at P1, posed with the platform at (0, y), horizontal; actuator springs are
    the allocation's (every joint passive in the model itself)."""
    pts = mech.ik(mech.POSES["P1"])
    xyz = lambda p: [float(p[0]), float(p[1]), 0.0]
    nodes = [{"id": n, "xyz": xyz(pts[j])} for j, pair in JOINT_NODES.items() for n in pair]
    nodes.append({"id": "P", "xyz": xyz(pts["P"])})
    return {"nodes": nodes,
            "elements": [{"id": i, "type": "rigid", "nodes": [a, b]} for i, a, b in LINKS],
            "joints": [{"id": j, "type": "revolute", "nodes": list(p), "axes": [[0, 0, 1]]} for j, p in JOINT_NODES.items()],
            "supports": [{"node": "J1g", "fix": "all"}, {"node": "J6g", "fix": "all"}],
            "pose": {"nodes": [{"node": "P", "xyz": [0.0, float(y), 0.0], "rotation": np.eye(3).tolist()}]},
            "analyses": [{"id": "alloc", "type": "actuator_allocation", "platform_node": "P",
                          "candidate_joints": list(JOINT_NODES), "actuators": 3, "actuator_stiffness": K_ACT,
                          "directions": DIRS, "schemes": SCHEMES, "rank_by": {"stiffness": "total", "direction": "uy"}}]}


@pytest.mark.filterwarnings("ignore:.*constraint rows are redundant")
@pytest.mark.parametrize("pose", list(mech.POSES))
def test_posed_lumped_allocation_equals_eq10_of_the_paper(pose):
    y = mech.POSES[pose]
    a = beamfea.run(bu_lumped(y))["analyses"]["alloc"]
    assert a["valid_schemes"] == 2, a["message"]
    expected = {}
    for scheme, s in zip(SCHEMES, a["schemes"]):
        assert s["valid"], s
        (p,) = s["poses"]
        assert p["status"] == "ok" and p["pose"] == "pose", p["message"]
        J, _ = mech.jac_analytic(mech.ik(y), scheme)  # eqs. 21-25 at the posed geometry
        KA = np.linalg.inv(J).T @ (K_ACT * np.eye(3)) @ np.linalg.inv(J)  # eq. 10
        scale = np.abs(KA).max()
        assert np.abs(np.asarray(p["actuated"]["K_jacobian"]) - KA).max() < TOL * scale
        assert np.abs(np.asarray(p["actuated"]["K_condensed"]) - KA).max() < TOL * scale
        # Rigid links: the frozen structure holds the platform, C_S = 0, the total is K_A.
        assert p["structural"]["held_directions"] == DIRS
        assert np.abs(np.asarray(p["structural"]["C"])).max() == 0.0
        assert np.abs(np.asarray(p["total"]["K_series"]) - KA).max() < TOL * scale
        assert np.abs(np.asarray(p["total"]["K_fea"]) - KA).max() < TOL * scale
        assert np.asarray(p["total"]["eq19"]) == pytest.approx(np.diag(KA), rel=TOL)
        # ranking value: total stiffness along y, 1 / C_yy with C = K_A^-1
        expected["+".join(scheme)] = 1.0 / np.linalg.inv(KA)[2, 2]
    order = sorted(expected, key=lambda k: -expected[k])
    assert [r["scheme"] for r in a["ranking"]] == order
    for r in a["ranking"]:
        assert r["worst_value"] == pytest.approx(expected[r["scheme"]], rel=TOL)
