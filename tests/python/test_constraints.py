"""Skewed supports, ties and linear constraints through beamfea.run: the reaction in the support's
frame (reaction_local), the tie forces, the same results as the program, and bad input as
beamfea.InputError naming the pointer."""
import math

import pytest

import beamfea
from conftest import assert_same, run_cli

L, E, G, A, I, J, P = 4.0, 2.0e11, 8.0e10, 1.0e-3, 2.0e-6, 1.0e-6, 1000.0


def inclined_roller(alpha):
    """A beam A-C-B along x, pinned at A, on a roller at B whose plane is inclined by alpha (its
    frame turned by alpha about z holds its uy and uz), loaded by P along -y at mid-span C."""
    c, s = math.cos(alpha), math.sin(alpha)
    beam = {"type": "beam", "material": "m", "section": "s", "orientation": [0, 0, 1]}
    return {
        "nodes": [{"id": "A", "xyz": [0, 0, 0]}, {"id": "C", "xyz": [L / 2, 0, 0]}, {"id": "B", "xyz": [L, 0, 0]}],
        "materials": [{"id": "m", "E": E, "G": G}],
        "sections": [{"id": "s", "A": A, "Iy": I, "Iz": I, "J": J}],
        "elements": [dict(beam, id="e1", nodes=["A", "C"]), dict(beam, id="e2", nodes=["C", "B"])],
        "supports": [{"node": "A", "fix": ["ux", "uy", "uz", "rx"]},
                     {"node": "B", "fix": ["uy", "uz"], "axes": [[c, s, 0], [-s, c, 0], [0, 0, 1]]}],
        "loads": [{"node": "C", "force": [0, -P, 0]}],
        "analyses": [{"id": "lin", "type": "linear_static"}],
    }


def test_inclined_roller_reaction_in_both_frames(tmp_path):
    # Statics: the roller's reaction N is along the plane's normal; moments about A give
    # N cos(alpha) L = P L / 2.
    alpha = math.radians(25.0)
    doc = inclined_roller(alpha)
    res = beamfea.run(doc)
    B = res["analyses"]["lin"]["nodes"]["B"]
    N = P / (2 * math.cos(alpha))
    assert B["reaction_local"][1] == pytest.approx(N, rel=1e-9)
    assert B["reaction_local"][0] == pytest.approx(0.0, abs=1e-9 * P)
    assert B["reaction"][0] == pytest.approx(-N * math.sin(alpha), rel=1e-9)
    assert B["reaction"][1] == pytest.approx(N * math.cos(alpha), rel=1e-9)
    assert "reaction_local" not in res["analyses"]["lin"]["nodes"]["A"]
    assert_same(res, run_cli(doc, tmp_path))


def test_tie_and_constraint_forces_and_bad_input():
    doc = inclined_roller(0.3)
    doc["nodes"].append({"id": "D", "xyz": [L / 2, 0, 1.0]})
    doc["elements"].append({"id": "e3", "type": "beam", "nodes": ["C", "D"], "material": "m", "section": "s",
                            "orientation": [1, 0, 0]})
    doc["constraints"] = [{"terms": [{"node": "D", "dof": "ux", "coefficient": 1.0}], "value": 0.001}]
    res = beamfea.run(doc)["analyses"]["lin"]
    assert res["nodes"]["D"]["displacement"][0] == pytest.approx(0.001, rel=1e-12)
    assert len(res["constraint_forces"]) == 1
    doc["ties"] = [{"nodes": ["C", "D"], "dofs": ["uz"]}, {"nodes": ["D", "C"], "dofs": ["uz"]}]
    with pytest.raises(beamfea.InputError) as e:
        beamfea.run(doc)
    assert "/ties/1" in str(e.value) and "redundant" in str(e.value)
