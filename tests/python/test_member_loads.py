"""Member loads, self-weight, load cases and a combination through the Python module:
a simply supported beam, its section forces along the member (`stations`) and end slopes against
the closed forms, and a combination against the factored sum; a bad load case as an InputError
naming its JSON pointer."""
import numpy as np
import pytest

import beamfea

# Steel IPE-like numbers (N, m); the closed forms hold for any.
L, E, G, A, IY, IZ, J, RHO, GRAV = 4.0, 2.1e11, 8.1e10, 2.8e-3, 1.4e-6, 1.9e-5, 7e-8, 7850.0, 9.81
P, W = 12e3, 3e3  # live point load at midspan (N), snow (N/m)
F_DEAD, F_LIVE, F_SNOW = 1.35, 1.5, 1.5
REL = 1e-9  # Hermite cubics give exact nodal values and exact statics for these loads


def beam(analyses):
    """Simply supported beam A (pin) - B (roller) along +x, local y = global y, two segments."""
    return {
        "nodes": [{"id": "A", "xyz": [0, 0, 0]}, {"id": "B", "xyz": [L, 0, 0]}],
        "materials": [{"id": "steel", "E": E, "G": G, "density": RHO}],
        "sections": [{"id": "s", "A": A, "Iy": IY, "Iz": IZ, "J": J}],
        "elements": [{"id": "e", "type": "beam", "nodes": ["A", "B"], "material": "steel", "section": "s",
                      "orientation": [0, 0, 1], "divisions": 2}],
        "supports": [{"node": "A", "fix": ["ux", "uy", "uz", "rx"]}, {"node": "B", "fix": ["uy", "uz"]}],
        "load_cases": [
            {"id": "dead", "gravity": [0, -GRAV, 0]},
            {"id": "live", "loads": [{"element": "e", "point": [0, -P, 0], "at": 0.5}]},
            {"id": "snow", "loads": [{"element": "e", "distributed": [0, -W, 0]}]},
        ],
        "combinations": [{"id": "uls", "factors": {"dead": F_DEAD, "live": F_LIVE, "snow": F_SNOW}}],
        "analyses": analyses,
    }


def moment(x, q, p):
    """Sagging moment of a simply supported beam under uniform q and a midspan load p (statics):
    q x (L - x) / 2 + p min(x, L - x) / 2; Mz > 0 on the positive face (docs/conventions.md)."""
    return q * x * (L - x) / 2 + p * min(x, L - x) / 2


def end_slope(q, p):
    """rz at A: -q L^3 / 24 EI - p L^2 / 16 EI (Roark, 8th ed., Table 8.1 cases 2e and 1e)."""
    return -q * L**3 / (24 * E * IZ) - p * L**2 / (16 * E * IZ)


CASES = {"dead": (RHO * A * GRAV, 0.0), "live": (0.0, P), "snow": (W, 0.0)}


@pytest.fixture(scope="module")
def results():
    analyses = [{"id": c, "type": "linear_static", "load_case": c, "stations": 7} for c in [*CASES, "uls"]]
    res = beamfea.run(beam(analyses))
    # All four cases share one factorisation (the run's linear system).
    assert res["factorizations"] == 1
    return res["analyses"]


def check(res, q, p):
    stations = res["elements"]["e"]["stations"]
    assert len(stations) >= 2 + 7
    scale = moment(L / 2, q, p)
    for st in stations:
        x, forces = st["x"], st["forces"]
        assert isinstance(forces, np.ndarray) and forces.shape == (6,)
        assert forces[5] == pytest.approx(moment(x, q, p), abs=REL * scale), x
    mid = [st for st in stations if abs(st["x"] - L / 2) < 1e-12]
    assert mid, "a station at midspan (segment end)"
    # qL^2/8 + PL/4 at midspan.
    assert mid[0]["forces"][5] == pytest.approx(q * L**2 / 8 + p * L / 4, rel=REL)
    assert res["nodes"]["A"]["displacement"][5] == pytest.approx(end_slope(q, p), rel=REL)
    # Reactions: half the total load each.
    assert res["nodes"]["A"]["reaction"][1] == pytest.approx((q * L + p) / 2, rel=REL)


@pytest.mark.parametrize("case", list(CASES))
def test_each_case_gives_the_simply_supported_closed_forms(results, case):
    q, p = CASES[case]
    assert results[case]["load_case"] == case
    check(results[case], q, p)


def test_combination_is_the_factored_sum(results):
    q = F_DEAD * CASES["dead"][0] + F_SNOW * CASES["snow"][0]
    p = F_LIVE * P
    check(results["uls"], q, p)
    # And equal to the factored sum of the cases' own results at the same x (away from the point
    # load, where the shear jumps and the cases list both sides or neither).
    parts = {c: results[c]["elements"]["e"]["stations"] for c in CASES}
    factor = {"dead": F_DEAD, "live": F_LIVE, "snow": F_SNOW}
    compared = 0
    for st in results["uls"]["elements"]["e"]["stations"]:
        if abs(st["x"] - L / 2) < 1e-9:
            continue
        want = sum(factor[c] * next(p["forces"] for p in parts[c] if abs(p["x"] - st["x"]) < 1e-12) for c in CASES)
        np.testing.assert_allclose(st["forces"], want, rtol=0, atol=REL * np.abs(want).max())
        compared += 1
    assert compared >= 7


def test_unknown_load_case_is_an_input_error_naming_its_pointer():
    with pytest.raises(beamfea.InputError) as e:
        beamfea.run(beam([{"id": "lin", "type": "linear_static", "load_case": "wind"}]))
    assert e.value.pointer == "/analyses/0/load_case"
    assert "wind" in str(e.value)


def test_actuator_allocation_with_a_load_case_reports_the_motor_torques():
    """A planar 2R arm (links 1 and 1, straight along x) holding a tip mass under gravity -y: the
    motors hold m g x 2 and m g x 1 (moments about their axes); the rigid-link sag with unit
    springs is 2 q_A + q_B, q = -tau (docs/analyses/actuator-allocation.md, "With a load case")."""
    m, g = 3.0, 9.81
    model = {
        "nodes": [{"id": "G", "xyz": [0, 0, 0]}, {"id": "A", "xyz": [0, 0, 0]}, {"id": "B1", "xyz": [1, 0, 0]},
                  {"id": "B2", "xyz": [1, 0, 0]}, {"id": "P", "xyz": [2, 0, 0]}],
        "materials": [{"id": "m", "E": 2.1e11, "nu": 0.3}],
        "sections": [{"id": "s", "shape": "circle", "r": 0.02}],
        "elements": [{"id": "L1", "type": "beam", "nodes": ["A", "B1"], "material": "m", "section": "s"},
                     {"id": "L2", "type": "beam", "nodes": ["B2", "P"], "material": "m", "section": "s"}],
        "joints": [{"id": "JA", "type": "revolute", "nodes": ["G", "A"], "axes": [[0, 0, 1]]},
                   {"id": "JB", "type": "revolute", "nodes": ["B1", "B2"], "axes": [[0, 0, 1]]}],
        "supports": [{"node": "G", "fix": "all"}],
        "masses": [{"node": "P", "mass": m}],
        "load_cases": [{"id": "payload", "gravity": [0, -g, 0]}],
        "analyses": [{"id": "alloc", "type": "actuator_allocation", "platform_node": "P",
                      "candidate_joints": ["JA", "JB"], "actuators": 2, "actuator_stiffness": 1.0,
                      "directions": ["rz", "uy"], "load_case": "payload",
                      "rank_by": {"stiffness": "loaded_total", "direction": "uy"}}],
    }
    res = beamfea.run(model)["analyses"]["alloc"]
    assert res["load_case"] == "payload"
    pose = res["schemes"][0]["poses"][0]
    efforts = [e["effort"] for e in pose["actuator_efforts"]]
    assert efforts == pytest.approx([2 * m * g, 1 * m * g], rel=REL)
    assert pose["platform_displacement"]["actuated"]["uy"] == pytest.approx(-(2 * 2 * m * g + 1 * m * g), rel=REL)
    # The weight across the horizontal arm: the loaded stiffness is reported, finite, per direction.
    assert np.isfinite(pose["loaded_stiffness"]["components"]["total"]["uy"])
    assert res["ranking"][0]["status"] == "ok"
