"""Stiffness indices of a stiffness analysis (docs/analyses/stiffness.md), from Python, the program
and a sweep, against the closed forms of a cantilever tip: with the moments free, the tip's
translational compliance is diag(L/EA, L^3/3EIz, L^3/3EIy) (Euler-Bernoulli, end loads)."""
import json
import subprocess

import numpy as np
import pytest

import beamfea
from conftest import EXE, cantilever, run_cli, assert_same

L, E, A, Iy, Iz = 2.0, 2.1e11, 1e-3, 2e-6, 3e-6
C_TT = np.diag([L / (E * A), L**3 / (3 * E * Iz), L**3 / (3 * E * Iy)])


def stiffness_model(**spec):
    return cantilever(analyses=[dict({"id": "K", "type": "stiffness", "node": "B"}, **spec)])


def test_indices_from_python_equal_the_closed_forms_and_the_program(tmp_path):
    d = [1.0, 2.0, 2.0]
    w = [10.0, -20.0, 30.0, 0.0, 0.0, 0.0]
    doc = stiffness_model(directions=[d], reference_wrench=w)
    res = beamfea.run(doc)
    ix = res["analyses"]["K"]["indices"]
    t = ix["translational"]
    c = np.diag(C_TT)
    np.testing.assert_allclose(t["min"], 1 / c.max(), rtol=1e-9)
    np.testing.assert_allclose(t["max"], 1 / c.min(), rtol=1e-9)
    np.testing.assert_allclose(t["directions"], [[0, 0, 1], [1, 0, 0]], atol=1e-9)
    np.testing.assert_allclose(ix["condition_translational"], c.max() / c.min(), rtol=1e-9)
    u = np.array(d) / np.linalg.norm(d)
    np.testing.assert_allclose(ix["along"], [1 / (u @ C_TT @ u)], rtol=1e-9)
    # Forces only: the translational part of C w is C_tt f (the rotations couple, not checked here).
    np.testing.assert_allclose(ix["deflection"][:3], C_TT @ w[:3], rtol=1e-9)
    np.testing.assert_allclose(ix["deflection_norm"], np.linalg.norm(C_TT @ w[:3]), rtol=1e-9)
    assert_same(res, run_cli(doc, tmp_path))


def test_a_supported_node_has_null_indices():
    ix = beamfea.run(cantilever(analyses=[{"id": "K", "type": "stiffness", "node": "A"}]))["analyses"]["K"]["indices"]
    assert ix["translational"]["min"] is None and ix["translational"]["max"] is None
    assert ix["condition_translational"] is None and ix["condition_rotational"] is None
    assert np.asarray(ix["translational"]["blocked"]).shape == (3, 3)


def test_indices_are_sweep_columns(tmp_path):
    (tmp_path / "base.json").write_text(json.dumps(stiffness_model()))
    lengths = [1.0, 2.0]
    spec = {"base": "base.json",
            "grid": [{"name": "L", "pointer": "/nodes/1/xyz/0", "values": lengths}],
            "outputs": [{"name": "k_min", "path": "analyses.K.indices.translational.min"},
                        {"name": "d_min", "path": "analyses.K.indices.translational.directions[0]"},
                        "analyses.K.indices.condition_translational"]}
    (tmp_path / "sweep.json").write_text(json.dumps(spec))
    cols = beamfea._beamfea.sweep(str(tmp_path / "sweep.json"), 1)
    Ls = np.array(lengths)
    np.testing.assert_allclose(cols["k_min"], 3 * E * Iy / Ls**3, rtol=1e-9)
    np.testing.assert_allclose(cols["d_min[2]"], [1.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(cols["analyses.K.indices.condition_translational"],
                               (Ls**3 / (3 * E * Iy)) / (Ls / (E * A)), rtol=1e-9)
