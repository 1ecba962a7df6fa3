"""Shared helpers of the Python tests: models as dicts, the program's answers, comparisons."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import beamfea

SOURCE_DIR = os.environ.get("BEAMFEA_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
EXE = os.environ.get("BEAMFEA_EXE", os.path.join(SOURCE_DIR, "build", "cli", "beamfea"))


def cantilever(L=2.0, E=2.1e11, G=8.1e10, A=1e-3, Iy=2e-6, Iz=3e-6, J=1e-6, load=(0, -1000.0, 0, 0, 0, 0),
               analyses=({"id": "lin", "type": "linear_static"},)):
    """A cantilever along +x from node A (fixed) to node B, one element, local z = global z."""
    return {
        "nodes": [{"id": "A", "xyz": [0, 0, 0]}, {"id": "B", "xyz": [L, 0, 0]}],
        "materials": [{"id": "m", "E": E, "G": G}],
        "sections": [{"id": "s", "A": A, "Iy": Iy, "Iz": Iz, "J": J}],
        "elements": [{"id": "e", "type": "beam", "nodes": ["A", "B"], "material": "m", "section": "s",
                      "orientation": [0, 0, 1]}],
        "supports": [{"node": "A", "fix": "all"}],
        "loads": [{"node": "B", "force": list(load[:3]), "moment": list(load[3:])}],
        "analyses": [dict(a) for a in analyses],
    }


def run_cli(doc, tmp_path, name="cli"):
    """The program's results.json for `doc` (run with --no-vtk in a folder of tmp_path)."""
    d = tmp_path / name
    d.mkdir()
    model = d / "model.json"
    model.write_text(json.dumps(doc))
    p = subprocess.run([EXE, "run", str(model), "--out", str(d / "out"), "--no-vtk", "-q"],
                       capture_output=True, text=True)
    assert p.returncode in (0, 1), p.stderr
    return json.loads((d / "out" / "results.json").read_text())


def assert_same(api, cli, where="", skip=("wall_time_s",)):
    """api (beamfea.run's result) equals cli (results.json) exactly: same keys, same numbers bit
    for bit (NaN in an array where the file has null), arrays as float64 ndarrays."""
    if isinstance(api, np.ndarray):
        assert api.dtype == np.float64, where
        ref = np.array(cli, dtype=float)  # null -> nan
        assert api.shape == ref.shape, f"{where}: shape {api.shape} vs {ref.shape}"
        same = (api == ref) | (np.isnan(api) & np.isnan(ref))
        assert same.all(), f"{where}: {api} vs {ref}"
    elif isinstance(api, dict):
        assert isinstance(cli, dict), where
        assert list(api.keys()) == list(cli.keys()), f"{where}: keys {list(api)} vs {list(cli)}"
        for k in api:
            if k not in skip:
                assert_same(api[k], cli[k], f"{where}/{k}", skip)
    elif isinstance(api, list):
        assert isinstance(cli, list) and len(api) == len(cli), where
        for i, (a, c) in enumerate(zip(api, cli)):
            assert_same(a, c, f"{where}/{i}", skip)
    elif isinstance(api, float):
        assert isinstance(cli, (int, float)) and not isinstance(cli, bool), where
        assert api == cli, f"{where}: {api!r} vs {cli!r}"
    else:
        assert type(api) is type(cli) and api == cli, f"{where}: {api!r} vs {cli!r}"


@pytest.fixture
def chdir_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path
