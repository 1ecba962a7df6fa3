"""Superelements and generated lumped models through the Python module."""
import numpy as np
import pytest

import beamfea
from conftest import cantilever

L, E, G, A, IY, IZ, J = 2.0, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6


def test_guyan_tip_stiffness_is_a_numpy_matrix_and_the_npz_holds_it(tmp_path):
    # The end-2 block of the Euler-Bernoulli member (Przemieniecki 1968, eq. 5.115): 12EI/L^3,
    # -6EI/L^2 (uy-rz), 4EI/L, EA/L, GJ/L; the same 6x6 in the .npz file.
    doc = cantilever(analyses=[{"id": "se", "type": "superelement", "interface": ["B"]}])
    doc["elements"][0]["divisions"] = 4
    res = beamfea.run(doc, out=tmp_path / "out", vtk=False)["analyses"]["se"]
    assert res["status"] == "ok"
    K = res["stiffness"]
    assert isinstance(K, np.ndarray) and K.shape == (6, 6)
    assert K[0, 0] == pytest.approx(E * A / L, rel=1e-9)
    assert K[1, 1] == pytest.approx(12 * E * IZ / L**3, rel=1e-9)
    assert K[1, 5] == pytest.approx(-6 * E * IZ / L**2, rel=1e-9)
    assert K[5, 5] == pytest.approx(4 * E * IZ / L, rel=1e-9)
    assert K[2, 4] == pytest.approx(6 * E * IY / L**2, rel=1e-9)
    assert K[3, 3] == pytest.approx(G * J / L, rel=1e-9)
    assert "mass" not in res  # no density, no point masses
    with np.load(tmp_path / "out" / "se_superelement.npz") as z:
        assert list(z.keys()) == ["stiffness"]
        np.testing.assert_array_equal(z["stiffness"], K)


def test_craig_bampton_with_mass_writes_both_arrays(tmp_path):
    doc = cantilever(analyses=[{"id": "cb", "type": "superelement", "interface": ["B"], "modes": 3}])
    doc["elements"][0]["divisions"] = 6
    doc["materials"][0]["density"] = 7850.0
    res = beamfea.run(doc, out=tmp_path / "out", vtk=False)["analyses"]["cb"]
    assert res["status"] == "ok"
    assert res["stiffness"].shape == (9, 9) and res["mass"].shape == (9, 9)
    f = res["frequencies"]
    assert f.shape == (3,) and np.all(np.diff(f) >= 0)
    # the modal block of the stiffness is diag(omega^2), the modal block of the mass the identity
    np.testing.assert_allclose(np.diag(res["stiffness"])[6:], (2 * np.pi * f) ** 2, rtol=1e-9)
    np.testing.assert_allclose(res["mass"][6:, 6:], np.eye(3), atol=1e-9)
    with np.load(tmp_path / "out" / "cb_superelement.npz") as z:
        np.testing.assert_array_equal(z["mass"], res["mass"])


def test_unknown_interface_node_raises():
    doc = cantilever(analyses=[{"id": "se", "type": "superelement", "interface": ["Q"]}])
    with pytest.raises(beamfea.InputError) as e:
        beamfea.run(doc)
    assert e.value.pointer == "/analyses/0/interface/0"


def arm():
    return {
        "nodes": [{"id": "O", "xyz": [0, 0, 0]}, {"id": "Ja", "xyz": [0.5, 0, 0]}, {"id": "Jb", "xyz": [0.5, 0, 0]},
                  {"id": "T", "xyz": [0.5, 0.4, 0]}],
        "materials": [{"id": "al", "E": 7e10, "G": 2.6e10}],
        "sections": [{"id": "c", "shape": "circle", "d": 0.03}],
        "elements": [{"id": "a", "type": "beam", "nodes": ["O", "Ja"], "material": "al", "section": "c", "divisions": 2},
                     {"id": "b", "type": "beam", "nodes": ["Jb", "T"], "material": "al", "section": "c", "divisions": 2}],
        "joints": [{"id": "j", "type": "revolute", "nodes": ["Ja", "Jb"], "axes": [[0, 0, 1]], "stiffness": [2e3]}],
        "supports": [{"node": "O", "fix": "all"}],
        "analyses": [{"id": "K", "type": "stiffness", "node": "T"}],
    }


def test_lumped_arm_has_the_beam_arms_tip_compliance(tmp_path):
    links = {"links": [{"id": "L1", "elements": ["a"], "base": "O", "tip": "Ja"},
                       {"id": "L2", "elements": ["b"], "base": "Jb", "tip": "T"}]}
    lumped = beamfea.lump(arm(), links, out=tmp_path / "lumped.json")
    assert (tmp_path / "lumped.json").exists()
    assert {j["id"] for j in lumped["joints"]} == {"j", "L1_spring", "L2_spring"}
    c_beam = beamfea.run(arm())["analyses"]["K"]["compliance"]
    c_vjm = beamfea.run(lumped)["analyses"]["K"]["compliance"]
    assert np.linalg.norm(c_vjm - c_beam) <= 1e-9 * np.linalg.norm(c_beam)


@pytest.mark.filterwarnings("ignore:.*is defined and never used")
def test_lumped_arm_loaded_compliance_agrees_to_the_order_of_the_load():
    # Under a tip force F the loaded-mode compliances (K + K_g about the reference, stiffness with
    # load_case) of the beam arm and of its generated lumped model differ by O(F / F_cr): the links'
    # own beam-column effect is not in a spring. Zeroth order: equal (condensation is exact for a
    # chain); first order: the difference grows linearly with the load and stays a small part of
    # the load's own effect on the compliance.
    links = {"links": [{"id": "L1", "elements": ["a"], "base": "O", "tip": "Ja"},
                       {"id": "L2", "elements": ["b"], "base": "Jb", "tip": "T"}]}
    diff, effect, load_ratio = {}, {}, {}
    for F in (10.0, 100.0):
        model = arm()
        model["loads"] = [{"node": "T", "force": [0.3 * F, -F, 0.2 * F]}]
        model["analyses"] = [{"id": "K", "type": "stiffness", "node": "T"},
                             {"id": "KL", "type": "stiffness", "node": "T", "load_case": "default"},
                             {"id": "B", "type": "buckling", "modes": 1}]
        beam, vjm = beamfea.run(model)["analyses"], beamfea.run(beamfea.lump(model, links))["analyses"]
        c0 = beam["K"]["compliance"]
        norm = np.linalg.norm(c0)
        assert np.linalg.norm(vjm["K"]["compliance"] - c0) <= 1e-9 * norm
        diff[F] = np.linalg.norm(vjm["KL"]["compliance"] - beam["KL"]["compliance"]) / norm
        effect[F] = np.linalg.norm(beam["KL"]["compliance"] - c0) / norm
        load_ratio[F] = 1.0 / beam["B"]["load_factors"][0]  # F / F_cr
    for F in diff:
        assert diff[F] <= 0.05 * load_ratio[F]
        assert diff[F] <= 0.03 * effect[F]
    assert 8.0 < diff[100.0] / diff[10.0] < 12.0  # first order in the load


def test_lump_unknown_element_raises_with_the_links_pointer():
    links = {"links": [{"id": "L1", "elements": ["a", "zz"], "base": "O", "tip": "Ja"}]}
    with pytest.raises(beamfea.InputError) as e:
        beamfea.lump(arm(), links)
    assert e.value.pointer == "/links/0/elements/1"
    assert "unknown element 'zz'" in str(e.value)
