"""Scale invariance: the same structure in two unit systems gives the same answers, each scaled
as its units say. No tolerance, step size or rank decision of the engine may depend on the unit
system: here lengths are scaled by a = 1e3 (m to mm) and forces by b = 1e-3 (N to kN), so that
moduli scale by b/a^2, second moments by a^4, densities (mass = force time^2 / length) by b/a^4.

Every analysis type runs on a space frame (four columns and four beams with a force and a moment
at a corner and self-weight), actuator_allocation on examples/02's planar 3-RRR manipulator with a
payload; results compared after scaling back, to 1e-9 of each array's largest
entry (the scaling by powers of ten rounds; a unit-dependent decision would differ by far more:
another step count, another rank, another mode).
"""
import copy
import os
import sys

import numpy as np
import pytest

import beamfea
from conftest import SOURCE_DIR

A_LEN, B_FORCE = 1e3, 1e-3
RTOL = 1e-9


def frame():
    h, w = 3.0, 4.0
    corners = [(0, 0), (w, 0), (w, w), (0, w)]
    nodes = [{"id": f"b{i}", "xyz": [x, y, 0.0]} for i, (x, y) in enumerate(corners)]
    nodes += [{"id": f"t{i}", "xyz": [x, y, h]} for i, (x, y) in enumerate(corners)]
    members = [{"id": f"c{i}", "type": "beam", "nodes": [f"b{i}", f"t{i}"], "material": "steel", "section": "col",
                "orientation": [1, 0, 0], "divisions": 4} for i in range(4)]
    members += [{"id": f"g{i}", "type": "beam", "nodes": [f"t{i}", f"t{(i + 1) % 4}"], "material": "steel",
                 "section": "beam", "orientation": [0, 0, 1], "divisions": 4} for i in range(4)]
    return {
        "nodes": nodes,
        "materials": [{"id": "steel", "E": 2.1e11, "G": 8.1e10, "density": 7850.0}],
        "sections": [{"id": "col", "A": 5e-3, "Iy": 4e-5, "Iz": 2e-5, "J": 1e-6},
                     {"id": "beam", "A": 4e-3, "Iy": 3e-5, "Iz": 1e-5, "J": 8e-7}],
        "elements": members,
        "supports": [{"node": f"b{i}", "fix": "all"} for i in range(4)],
        "loads": [{"node": "t2", "force": [2.0e4, 1.0e4, -5.0e4], "moment": [1.0e3, -2.0e3, 3.0e3]}],
        "gravity": [0.0, 0.0, -9.81],
        "analyses": [
            {"id": "lin", "type": "linear_static"},
            {"id": "K", "type": "stiffness", "node": "t2"},
            {"id": "buck", "type": "buckling", "modes": 3},
            {"id": "modal", "type": "modal", "modes": 4},
            {"id": "so", "type": "second_order"},
            {"id": "path", "type": "path", "track": ["t2"], "control": {"load_factor": 3.0, "increments": 6}},
            {"id": "arc", "type": "path", "track": ["t2"], "control": {"arc_length": "auto"}, "stop": {"steps": 5}},
        ],
    }


def scaled(doc, a=A_LEN, b=B_FORCE):
    d = copy.deepcopy(doc)
    for n in d["nodes"]:
        n["xyz"] = [a * x for x in n["xyz"]]
    for m in d["materials"]:
        m["E"] *= b / a**2
        m["G"] *= b / a**2
        m["density"] *= b / a**4
    for s in d["sections"]:
        s["A"] *= a**2
        for k in ("Iy", "Iz", "J"):
            s[k] *= a**4
    for load in d["loads"]:
        load["force"] = [b * f for f in load["force"]]
        load["moment"] = [a * b * m for m in load["moment"]]
    d["gravity"] = [a * g for g in d["gravity"]]
    return d


def close(x, y, where):
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    assert x.shape == y.shape, where
    np.testing.assert_allclose(x, y, rtol=0, atol=RTOL * max(np.abs(y).max(), 1e-300), err_msg=where)


# A node's 6-vector: translations scale by a, rotations by 1; forces by b, moments by a b.
DISP = np.array([A_LEN] * 3 + [1.0] * 3)
WRENCH = np.array([B_FORCE] * 3 + [A_LEN * B_FORCE] * 3)


@pytest.fixture(scope="module")
def both():
    return beamfea.run(frame()), beamfea.run(scaled(frame()))


def test_every_analysis_succeeds_in_both_unit_systems(both):
    for res in both:
        for id_, r in res["analyses"].items():
            assert r["status"] == "ok", (id_, r.get("message"))


def test_linear_and_second_order_displacements_reactions_and_end_forces_scale(both):
    si, mm = both
    for id_ in ("lin", "so"):
        for n, v in si["analyses"][id_]["nodes"].items():
            close(mm["analyses"][id_]["nodes"][n]["displacement"] / DISP, v["displacement"], f"{id_} {n} u")
            if "reaction" in v:
                close(mm["analyses"][id_]["nodes"][n]["reaction"] / WRENCH, v["reaction"], f"{id_} {n} R")
        for e, v in si["analyses"][id_]["elements"].items():
            ef_mm = np.asarray(mm["analyses"][id_]["elements"][e]["end_forces"])
            close(ef_mm.reshape(-1, 6) / WRENCH, np.asarray(v["end_forces"]).reshape(-1, 6), f"{id_} {e} end forces")


def test_the_stiffness_matrix_scales_block_by_block(both):
    si, mm = both
    K_si, K_mm = np.asarray(si["analyses"]["K"]["matrix"]), np.asarray(mm["analyses"]["K"]["matrix"])
    # K maps displacements to wrenches: K_mm = diag(WRENCH) K_si diag(1/DISP).
    close(K_mm, np.diag(WRENCH) @ K_si @ np.diag(1 / DISP), "K")
    assert si["analyses"]["K"]["rank"] == mm["analyses"]["K"]["rank"]


def test_buckling_load_factors_and_frequencies_do_not_change(both):
    si, mm = both
    close(mm["analyses"]["buck"]["load_factors"], si["analyses"]["buck"]["load_factors"], "buckling")
    close(mm["analyses"]["modal"]["frequencies"], si["analyses"]["modal"]["frequencies"], "modal")


def test_paths_take_the_same_steps_to_the_same_load_factors(both):
    si, mm = both
    for id_ in ("path", "arc"):
        s_si, s_mm = si["analyses"][id_]["steps"], mm["analyses"][id_]["steps"]
        assert len(s_si) == len(s_mm), id_
        assert [s["iterations"] for s in s_si] == [s["iterations"] for s in s_mm], id_
        close([s["load_factor"] for s in s_mm], [s["load_factor"] for s in s_si], f"{id_} load factors")
        close([np.asarray(s["nodes"]["t2"]["displacement"]) / DISP for s in s_mm],
              [s["nodes"]["t2"]["displacement"] for s in s_si], f"{id_} displacements")
        assert si["analyses"][id_]["termination"] == mm["analyses"][id_]["termination"]


def bu_manipulator():
    """examples/02's planar 3-RRR (Bu 2012) with a payload: actuator_allocation's model."""
    sys.path.insert(0, os.path.join(SOURCE_DIR, "examples", "02_bu_planar_manipulator"))
    try:
        import bu_example
    finally:
        sys.path.pop(0)
    poses = {k: bu_example.inverse_kinematics(y) for k, y in bu_example.POSES.items()}
    m = bu_example.model(poses)
    m["analyses"] = [a for a in m["analyses"] if a["id"] in ("all_terms", "payload")]
    return m


def scaled_bu(doc, a=A_LEN, b=B_FORCE):
    d = copy.deepcopy(doc)
    for n in d["nodes"]:
        n["xyz"] = [a * x for x in n["xyz"]]
    d["materials"][0]["E"] *= b / a**2
    d["sections"][0]["r"] *= a
    for case in d["load_cases"]:
        for load in case["loads"]:
            load["force"] = [b * f for f in load["force"]]
    for an in d["analyses"]:
        an["actuator_stiffness"] *= a * b  # a revolute actuator: moment per radian
        an["poses"] = copy.deepcopy(an["poses"])  # the analyses share one list: scaled once each
        for pose in an["poses"]:
            for n in pose["nodes"]:
                n["xyz"] = [a * x for x in n["xyz"]]
    return d


def test_actuator_allocation_stiffnesses_efforts_and_ranking_scale():
    si, mm = beamfea.run(bu_manipulator()), beamfea.run(scaled_bu(bu_manipulator()))
    # Directions rz, ux, uy: displacements scale by (1, a, a), forces by (a b, b, b).
    D, W = np.array([1.0, A_LEN, A_LEN]), np.array([A_LEN * B_FORCE, B_FORCE, B_FORCE])
    for id_ in ("all_terms", "payload"):
        r_si, r_mm = si["analyses"][id_], mm["analyses"][id_]
        assert r_si["status"] == r_mm["status"] == "ok"
        assert [s["scheme"] for s in r_si["ranking"]] == [s["scheme"] for s in r_mm["ranking"]], id_
        for s_si, s_mm in zip(r_si["schemes"], r_mm["schemes"]):
            assert s_si["valid"] == s_mm["valid"]
            for p_si, p_mm in zip(s_si["poses"], s_mm["poses"]):
                where = f"{id_} {s_si['scheme']} {p_si['pose']}"
                assert p_si["status"] == p_mm["status"], where
                if p_si["status"] != "ok":
                    continue
                for part, key in (("actuated", "K_condensed"), ("structural", "K_fea"), ("total", "K_fea")):
                    close(np.diag(1 / W) @ p_mm[part][key] @ np.diag(D), p_si[part][key], f"{where} {part}")
                if id_ == "payload":
                    close([e["effort"] / (A_LEN * B_FORCE) for e in p_mm["actuator_efforts"]],
                          [e["effort"] for e in p_si["actuator_efforts"]], f"{where} efforts")
                    u_si, u_mm = p_si["platform_displacement"]["total"], p_mm["platform_displacement"]["total"]
                    close([u_mm["rz"], u_mm["ux"] / A_LEN, u_mm["uy"] / A_LEN], [u_si["rz"], u_si["ux"], u_si["uy"]],
                          f"{where} displacement")
                    close(np.diag(1 / W) @ p_mm["loaded_stiffness"]["total"] @ np.diag(D),
                          p_si["loaded_stiffness"]["total"], f"{where} loaded")
