"""The foundation's closed forms through beamfea.run, and the same answers as the program, bit
for bit (both run load_and_check and run_document; results.json keeps doubles exactly)."""
import math

import numpy as np
import pytest

import beamfea
from conftest import assert_same, cantilever, run_cli

L, E, G, A, IY, IZ, J = 2.0, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6
REL = 1e-9  # one Hermite element is exact for end loads; only round-off remains


def tip(res, analysis="lin"):
    return res["analyses"][analysis]["nodes"]["B"]["displacement"]


def test_cantilever_tip_force_gives_PL3_over_3EI():
    # Gere & Timoshenko, Mechanics of Materials, Table G-1 case 4: v = P L^3 / 3EI, theta = P L^2 / 2EI.
    P = 1000.0
    u = tip(beamfea.run(cantilever(load=(0, -P, 0, 0, 0, 0))))
    assert u[1] == pytest.approx(-P * L**3 / (3 * E * IZ), rel=REL)
    assert u[5] == pytest.approx(-P * L**2 / (2 * E * IZ), rel=REL)
    u = tip(beamfea.run(cantilever(load=(0, 0, -P, 0, 0, 0))))
    assert u[2] == pytest.approx(-P * L**3 / (3 * E * IY), rel=REL)
    assert u[4] == pytest.approx(+P * L**2 / (2 * E * IY), rel=REL)  # right-hand rule about y


def test_cantilever_tip_moment_axial_force_and_torque():
    # Tip moment M: theta = M L / EI, v = M L^2 / 2EI; axial N: u = N L / EA; torque T: phi = T L / GJ.
    M, N, T = 50.0, 2.0e4, 30.0
    u = tip(beamfea.run(cantilever(load=(N, 0, 0, T, 0, M))))
    assert u[0] == pytest.approx(N * L / (E * A), rel=REL)
    assert u[3] == pytest.approx(T * L / (G * J), rel=REL)
    assert u[5] == pytest.approx(M * L / (E * IZ), rel=REL)
    assert u[1] == pytest.approx(M * L**2 / (2 * E * IZ), rel=REL)


def test_reaction_balances_the_load():
    P = 1000.0
    r = beamfea.run(cantilever(load=(0, -P, 0, 0, 0, 0)))["analyses"]["lin"]["nodes"]["A"]["reaction"]
    # Statics: R_y = P, M_z = P L at the clamp.
    assert r[1] == pytest.approx(P, rel=REL)
    assert r[5] == pytest.approx(P * L, rel=REL)


def test_tip_stiffness_is_the_element_end_block():
    # Przemieniecki, Theory of Matrix Structural Analysis (1968), eq. 5.116: the j-end block.
    res = beamfea.run(cantilever(analyses=[{"id": "K", "type": "stiffness", "node": "B"}]))
    K = res["analyses"]["K"]["matrix"]
    assert K.shape == (6, 6) and K.dtype == np.float64
    expect = {(0, 0): E * A / L, (1, 1): 12 * E * IZ / L**3, (2, 2): 12 * E * IY / L**3, (3, 3): G * J / L,
              (4, 4): 4 * E * IY / L, (5, 5): 4 * E * IZ / L, (1, 5): -6 * E * IZ / L**2, (2, 4): 6 * E * IY / L**2}
    for (i, j), k in expect.items():
        assert K[i, j] == pytest.approx(k, rel=1e-9), (i, j)
        assert K[j, i] == pytest.approx(k, rel=1e-9), (j, i)
    assert res["analyses"]["K"]["rank"] == 6
    assert res["analyses"]["K"]["compliance_bounded"] is True
    assert len(res["analyses"]["K"]["unbounded_directions"]) == 0


def test_a_node_that_spins_freely_has_unbounded_rotations_not_zero_compliance():
    # A node C behind a spherical joint at the tip: its translations are the cantilever tip's,
    # ux = L / (E A), uy = L^3 / (3 E Iz) per unit force (Euler-Bernoulli), its rotations free. The
    # compliance holds 0 there by convention; compliance_bounded and unbounded_directions say so.
    doc = cantilever(analyses=[{"id": "K", "type": "stiffness", "node": "C"}])
    doc["nodes"].append({"id": "C", "xyz": [L, 0, 0]})
    doc["joints"] = [{"id": "S", "type": "spherical", "nodes": ["B", "C"]}]
    k = beamfea.run(doc)["analyses"]["K"]
    C = np.asarray(k["compliance"])
    assert C[0, 0] == pytest.approx(L / (E * A), rel=1e-9)
    assert C[1, 1] == pytest.approx(L**3 / (3 * E * IZ), rel=1e-9)
    assert np.all(C[3:, 3:] == 0.0)
    assert k["compliance_bounded"] is False
    U = np.asarray(k["unbounded_directions"])
    assert U.shape == (3, 6)
    # they span exactly the three rotations
    assert np.allclose(U[:, :3], 0.0, atol=1e-12)
    assert np.linalg.matrix_rank(U[:, 3:]) == 3


def test_cantilever_buckles_at_the_euler_load():
    # Euler, fixed-free column: P_cr = pi^2 E I / (4 L^2) (Timoshenko & Gere, Theory of Elastic
    # Stability, 2.1). 8 cubic elements: the FE load factor is within 1e-5 above it.
    doc = cantilever(load=(-1.0, 0, 0, 0, 0, 0), analyses=[{"id": "b", "type": "buckling", "modes": 2}])
    doc["elements"][0]["divisions"] = 8
    lf = beamfea.run(doc)["analyses"]["b"]["load_factors"]
    assert isinstance(lf, np.ndarray) and lf.dtype == np.float64
    euler = math.pi**2 * E * min(IY, IZ) / (4 * L**2)
    assert lf[0] == pytest.approx(euler, rel=1e-4)
    assert lf[0] >= euler * (1 - 1e-9)  # a conforming cubic mesh is stiffer: from above


@pytest.mark.parametrize("analyses", [
    [{"id": "lin", "type": "linear_static"}],
    [{"id": "K", "type": "stiffness", "node": "B"}],
    [{"id": "b", "type": "buckling", "modes": 3}],
])
def test_same_answers_as_the_program_bit_for_bit(tmp_path, analyses):
    doc = cantilever(load=(-3.0e3, -1000.0, 500.0, 20.0, -10.0, 5.0), analyses=analyses)
    doc["elements"][0]["divisions"] = 4
    assert_same(beamfea.run(doc), run_cli(doc, tmp_path))


def test_space_frame_example_equals_the_program(tmp_path):
    import json
    import os
    from conftest import SOURCE_DIR
    path = os.path.join(SOURCE_DIR, "examples", "01_space_frame", "model.json")
    with open(path) as f:
        doc = json.load(f)
    api = beamfea.run(path)
    assert_same(api, run_cli(doc, tmp_path))
    assert_same(beamfea.run(doc), api)
