"""URDF import from Python (docs/urdf.md): beamfea.from_urdf returns the model the program's
`beamfea urdf` writes, and the model runs. A planar RRP arm (two revolute joints about z, a slider
along the second link) on joint springs K: the tool compliance equals J K^-1 J^T, J the Jacobian
of the zero pose computed here (columns z x (p - p_i) for the revolute joints, a for the slider)."""
import json
import subprocess

import numpy as np
import pytest

import beamfea
from conftest import EXE

URDF = """<robot name="rrp">
  <link name="base"/><link name="upper"/><link name="fore"/><link name="tip"/><link name="tool"/>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.2" rpy="0 0 0.5"/><axis xyz="0 0 1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="0.6 0 0" rpy="0 0 -1.1"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="slide" type="prismatic"><parent link="fore"/><child link="tip"/>
    <origin xyz="0.3 0 0"/><axis xyz="1 0 0"/><limit lower="0" upper="0.3" effort="1" velocity="1"/></joint>
  <joint name="flange" type="fixed"><parent link="tip"/><child link="tool"/><origin xyz="0.1 0 0"/></joint>
</robot>
"""
K = {"shoulder": 3.0e4, "elbow": 1.2e4, "slide": 4.0e5}
SIDECAR = {"joints": {name: {"stiffness": [k]} for name, k in K.items()}}


def reader_knows_limits():
    probe = {"nodes": [{"id": "a", "xyz": [0, 0, 0]}, {"id": "b", "xyz": [0, 0, 0]}],
             "joints": [{"id": "j", "type": "revolute", "nodes": ["a", "b"], "axes": [[0, 0, 1]], "limits": [[-1, 1]]}],
             "supports": [{"node": "a", "fix": "all"}]}
    try:
        beamfea.check(probe)
        return True
    except beamfea.InputError:
        return False


def runnable(model):
    """Joint limits are for poses: stripped where the model reader does not know them yet."""
    if not reader_knows_limits():
        for j in model.get("joints", []):
            j.pop("limits", None)
    return model


def test_from_urdf_equals_the_program_and_its_compliance_is_j_kinv_jt(tmp_path):
    robot = tmp_path / "rrp.urdf"
    robot.write_text(URDF)
    car = tmp_path / "flex.json"
    car.write_text(json.dumps(SIDECAR))
    model = beamfea.from_urdf(robot, sidecar=SIDECAR)
    assert beamfea.from_urdf(str(robot), sidecar=car) == model
    p = subprocess.run([EXE, "urdf", str(robot), "--sidecar", str(car), "-o", str(tmp_path / "m.json")],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert json.loads((tmp_path / "m.json").read_text()) == model
    assert [j["id"] for j in model["joints"]] == ["shoulder", "elbow", "slide"]
    assert [j["type"] for j in model["joints"]] == ["revolute", "revolute", "prismatic"]

    # Zero pose, planar: shoulder at (0, 0, 0.2) turned by 0.5, elbow at 0.6 along it, turned by
    # -1.1, the slider 0.3 further along the forearm, the tool 0.1 beyond.
    a1, a2 = 0.5, 0.5 - 1.1
    e1, e2 = np.array([np.cos(a1), np.sin(a1), 0]), np.array([np.cos(a2), np.sin(a2), 0])
    p1 = np.array([0, 0, 0.2])
    p2 = p1 + 0.6 * e1
    tool = p2 + 0.4 * e2
    tool_node = next(n for n in model["nodes"] if n["id"] == "tool")
    np.testing.assert_allclose(tool_node["xyz"], tool, atol=1e-12)
    z = np.array([0, 0, 1.0])
    J = np.zeros((6, 3))
    J[:3, 0], J[3:, 0] = np.cross(z, tool - p1), z
    J[:3, 1], J[3:, 1] = np.cross(z, tool - p2), z
    J[:3, 2] = e2
    C = J @ np.diag([1 / K["shoulder"], 1 / K["elbow"], 1 / K["slide"]]) @ J.T

    model = runnable(model)
    model["analyses"] = [{"id": "k", "type": "stiffness", "node": "tool"}]
    res = beamfea.run(model)["analyses"]["k"]
    assert res["status"] == "ok"
    np.testing.assert_allclose(res["compliance"], C, rtol=0, atol=1e-9 * np.abs(C).max())


def test_a_bad_sidecar_is_an_input_error_at_its_pointer(tmp_path):
    robot = tmp_path / "rrp.urdf"
    robot.write_text(URDF)
    with pytest.raises(beamfea.InputError) as e:
        beamfea.from_urdf(robot, sidecar={"joints": {"elbw": {"stiffness": [1.0]}}})
    assert e.value.pointer == "/joints/elbw"
    assert "did you mean 'elbow'" in str(e.value)
    with pytest.raises(beamfea.InputError) as e:
        beamfea.from_urdf(robot, sidecar={"joints": {"flange": {"stiffness": [1.0]}}})
    assert "flange" in str(e.value)
    with pytest.raises(beamfea.InputError) as e:
        beamfea.from_urdf(tmp_path / "missing.urdf")
    assert "missing.urdf" in str(e.value)


def test_a_urdf_arm_at_a_pose_is_the_product_of_its_transforms_and_keeps_its_limits(tmp_path):
    """pose.joints names the URDF's joints: the tool goes where the chain of URDF transforms with
    the joint motions puts it (planar here: angles add about z, the slide runs along the forearm),
    its compliance is J(q) K^-1 J(q)^T, and a value outside a URDF <limit> is bad input naming it."""
    robot = tmp_path / "rrp.urdf"
    robot.write_text(URDF)
    model = beamfea.from_urdf(robot, sidecar=SIDECAR)
    q = {"shoulder": 0.3, "elbow": -0.4, "slide": 0.2}
    model["pose"] = {"joints": dict(q)}
    model["analyses"] = [{"id": "k", "type": "stiffness", "node": "tool"}]
    res = beamfea.run(model)
    a1 = 0.5 + q["shoulder"]
    a2 = a1 - 1.1 + q["elbow"]
    e1, e2 = np.array([np.cos(a1), np.sin(a1), 0]), np.array([np.cos(a2), np.sin(a2), 0])
    p1 = np.array([0, 0, 0.2])
    p2 = p1 + 0.6 * e1
    tool = p2 + (0.4 + q["slide"]) * e2
    np.testing.assert_allclose(res["pose"]["nodes"]["tool"], tool, atol=1e-12)
    for name, v in q.items():
        assert res["pose"]["joints"][name] == pytest.approx(v, abs=1e-14)
    z = np.array([0, 0, 1.0])
    J = np.zeros((6, 3))
    J[:3, 0], J[3:, 0] = np.cross(z, tool - p1), z
    J[:3, 1], J[3:, 1] = np.cross(z, tool - p2), z
    J[:3, 2] = e2
    C = J @ np.diag([1 / K["shoulder"], 1 / K["elbow"], 1 / K["slide"]]) @ J.T
    k = res["analyses"]["k"]
    assert k["status"] == "ok"
    np.testing.assert_allclose(k["compliance"], C, rtol=0, atol=1e-9 * np.abs(C).max())

    for name, bad in (("elbow", 2.5), ("slide", 0.4)):
        model["pose"] = {"joints": {name: bad}}
        with pytest.raises(beamfea.InputError) as e:
            beamfea.run(model)
        assert name in str(e.value) and "limit" in str(e.value)
