"""Member loads, self-weight, load cases and a combination through the Python module (issue 12):
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
