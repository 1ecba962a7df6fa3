"""Stiffness indices and the compliance ellipsoid of a stiffness analysis (docs/analyses/stiffness.md),
from Python, the program and a sweep, against the closed forms of a cantilever tip: with the moments
free, the tip's translational compliance is diag(L/EA, L^3/3EIz, L^3/3EIy) (Euler-Bernoulli,
end loads); the ellipsoid file is read back with VTK's own reader."""
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
    cols = beamfea._beamfea.sweep(str(tmp_path / "sweep.json"), 1, None)
    Ls = np.array(lengths)
    np.testing.assert_allclose(cols["k_min"], 3 * E * Iy / Ls**3, rtol=1e-9)
    np.testing.assert_allclose(cols["d_min[2]"], [1.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(cols["analyses.K.indices.condition_translational"],
                               (Ls**3 / (3 * E * Iy)) / (Ls / (E * A)), rtol=1e-9)


def read_polydata(path):
    import vtk  # Debian python3-vtk9, beside libvtk9-dev (scripts/install-deps.sh)
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(str(path))
    r.Update()
    poly = r.GetOutput()
    assert poly.GetNumberOfPoints() > 0 and poly.GetNumberOfCells() > 0
    from vtk.util.numpy_support import vtk_to_numpy
    points = vtk_to_numpy(poly.GetPoints().GetData())
    fd = poly.GetFieldData()
    field = {fd.GetArrayName(i): vtk_to_numpy(fd.GetArray(i)) for i in range(fd.GetNumberOfArrays())}
    return poly, points, field


def test_the_ellipsoid_file_opens_and_its_extent_is_the_semi_axes(tmp_path):
    res = beamfea.run(stiffness_model(ellipsoid=True), out=tmp_path / "o")
    el = res["analyses"]["K"]["ellipsoid"]
    assert el["file"] == "K_ellipsoid.vtp"
    poly, points, field = read_polydata(tmp_path / "o" / "K_ellipsoid.vtp")
    # The scale draws the largest semi-axis at 0.1 of the model size (its bounding-box diagonal, L).
    c = np.diag(C_TT)
    scale = 0.1 * L / c.max()
    np.testing.assert_allclose(el["scale"], scale, rtol=1e-9)
    np.testing.assert_allclose(field["scale"], [scale], rtol=1e-9)
    np.testing.assert_allclose(el["semi_axes"], sorted(c, reverse=True), rtol=1e-9)
    # Centred at B = (L, 0, 0); axes along x, y, z here: the bounds are B -+ scale * compliance.
    xmin, xmax, ymin, ymax, zmin, zmax = poly.GetBounds()
    half = np.array([xmax - xmin, ymax - ymin, zmax - zmin]) / 2
    centre = np.array([xmax + xmin, ymax + ymin, zmax + zmin]) / 2
    np.testing.assert_allclose(half, scale * c, rtol=1e-9)
    np.testing.assert_allclose(centre, [L, 0, 0], atol=1e-12)
    # Every point is on the ellipsoid: sum (x_i / a_i)^2 = 1 in its axes.
    axes = np.asarray(el["axes"])
    a = scale * np.asarray(el["semi_axes"])
    local = (points - [L, 0, 0]) @ axes.T
    np.testing.assert_allclose(((local / a) ** 2).sum(axis=1), 1.0, rtol=1e-9)


def test_the_ellipsoid_of_a_rotated_cantilever_has_its_rotated_extent(tmp_path):
    # The cantilever along (1, 1, 0) / sqrt 2: the compliance's axes turn with it.
    doc = stiffness_model(ellipsoid=True)
    s = np.sqrt(0.5)
    doc["nodes"][1]["xyz"] = [L * s, L * s, 0.0]
    res = beamfea.run(doc, out=tmp_path / "o")
    el = res["analyses"]["K"]["ellipsoid"]
    poly, points, _ = read_polydata(tmp_path / "o" / "K_ellipsoid.vtp")
    c = np.diag(C_TT)
    scale = 0.1 * L / c.max()
    axial = np.array([s, s, 0.0])
    lateral = np.array([-s, s, 0.0])
    rel = points - [L * s, L * s, 0]
    # The extent along each principal direction: the semi-axes.
    for d, ci in ((axial, c[0]), (lateral, c[1]), (np.array([0, 0, 1.0]), c[2])):
        np.testing.assert_allclose((rel @ d).max(), scale * ci, rtol=1e-9)
        np.testing.assert_allclose(-(rel @ d).min(), scale * ci, rtol=1e-9)
    assert abs(abs(np.asarray(el["axes"][0]) @ [0, 0, 1.0]) - 1) < 1e-9  # largest: z (Iy smallest)


def test_no_ellipsoid_file_without_vtk_output(tmp_path):
    model = tmp_path / "m.json"
    model.write_text(json.dumps(stiffness_model(ellipsoid=True)))
    subprocess.run([EXE, "run", str(model), "--out", str(tmp_path / "out"), "--no-vtk", "-q"], check=True)
    assert not (tmp_path / "out" / "K_ellipsoid.vtp").exists()
    res = json.loads((tmp_path / "out" / "results.json").read_text())
    assert "file" not in res["analyses"]["K"]["ellipsoid"]


def test_a_kept_sweep_plays_the_ellipsoids_as_a_series(tmp_path):
    # Two tip positions: the tip compliance grows as L^3 (bending) and L (axial).
    (tmp_path / "base.json").write_text(json.dumps(stiffness_model(ellipsoid=True)))
    lengths = [1.0, 2.0]
    spec = {"base": "base.json", "grid": [{"name": "L", "pointer": "/nodes/1/xyz/0", "values": lengths}],
            "outputs": ["analyses.K.ellipsoid.scale"]}
    (tmp_path / "sweep.json").write_text(json.dumps(spec))
    subprocess.run([EXE, "sweep", str(tmp_path / "sweep.json"), "--out", str(tmp_path / "out"), "--keep", "-q",
                    "--jobs", "2"], check=True)
    import xml.etree.ElementTree as ET
    sets = ET.parse(tmp_path / "out" / "K_ellipsoid.pvd").getroot().findall("./Collection/DataSet")
    assert [(float(s.get("timestep")), s.get("file")) for s in sets] == \
        [(0.0, "cases/0/K_ellipsoid.vtp"), (1.0, "cases/1/K_ellipsoid.vtp")]
    for s, Lc in zip(sets, lengths):
        poly, _, field = read_polydata(tmp_path / "out" / s.get("file"))
        # The largest semi-axis (z bending, L^3 / 3 E Iy) drawn at 0.1 of that case's model size Lc.
        zmin, zmax = poly.GetBounds()[4:]
        np.testing.assert_allclose((zmax - zmin) / 2, 0.1 * Lc, rtol=1e-9)
        np.testing.assert_allclose(field["semi_axes"][0], Lc**3 / (3 * E * Iy), rtol=1e-9)
