"""Member end releases, rigid end zones and offsets through beamfea.run: the keys are accepted,
the answers are the closed forms and the program's, bad values raise InputError naming the field."""
import pytest

import beamfea
from conftest import assert_same, cantilever, run_cli

L, E, G, A, IY, IZ, J = 2.0, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6
P = 1000.0


def test_pinned_end_by_releases_gives_the_propped_cantilever(tmp_path):
    # A member clamped at A, its end at B pinned by the release (B held in translation), a uniform
    # load q: R_B = 3 q L / 8, M_A = q L^2 / 8 (Roark, Formulas for Stress and Strain, Table 8.1 2e).
    q = 1500.0
    doc = cantilever(load=(0, 0, 0, 0, 0, 0))
    doc["elements"][0]["divisions"] = 4
    doc["elements"][0]["releases"] = {"end": ["ry", "rz"]}
    doc["supports"].append({"node": "B", "fix": "all"})
    doc["loads"] = [{"element": "e", "distributed": [0, -q, 0]}]
    res = beamfea.run(doc)
    nodes = res["analyses"]["lin"]["nodes"]
    assert nodes["B"]["reaction"][1] == pytest.approx(3 * q * L / 8, rel=1e-9)
    assert nodes["A"]["reaction"][5] == pytest.approx(q * L**2 / 8, rel=1e-9)
    assert_same(res, run_cli(doc, tmp_path))


def test_eccentric_cantilever_and_rigid_ends(tmp_path):
    # Axis offset e along z: a tip force P (y) twists the member by e P, v_B = P L^3/(3 E Iz) + e^2 P L/(G J).
    e = 0.15
    doc = cantilever(load=(0, P, 0, 0, 0, 0))
    doc["elements"][0]["offsets"] = {"start": [0, 0, e], "end": [0, 0, e]}
    res = beamfea.run(doc)
    v = P * L**3 / (3 * E * IZ) + e**2 * P * L / (G * J)
    assert res["analyses"]["lin"]["nodes"]["B"]["displacement"][1] == pytest.approx(v, rel=1e-9)
    assert_same(res, run_cli(doc, tmp_path))
    # Rigid end r at the clamp: the tip deflects as a cantilever of length L - r.
    r = 0.4
    doc = cantilever(load=(0, P, 0, 0, 0, 0))
    doc["elements"][0]["rigid_ends"] = [r, 0.0]
    res = beamfea.run(doc)
    assert res["analyses"]["lin"]["nodes"]["B"]["displacement"][1] == pytest.approx(P * (L - r)**3 / (3 * E * IZ), rel=1e-9)


def test_bad_releases_and_rigid_ends_raise_input_error():
    doc = cantilever()
    doc["elements"][0]["releases"] = {"start": ["rx"], "end": ["rx"]}
    with pytest.raises(beamfea.InputError, match="/elements/0/releases"):
        beamfea.run(doc)
    doc = cantilever()
    doc["elements"][0]["rigid_ends"] = [1.0, 1.0]
    with pytest.raises(beamfea.InputError, match="/elements/0/rigid_ends"):
        beamfea.run(doc)
