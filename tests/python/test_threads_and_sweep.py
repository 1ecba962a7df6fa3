"""Cases on a thread pool give the serial answers (the engine runs with the GIL released), and
beamfea.sweep gives the program's table."""
import csv
import json
import os
import subprocess
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import beamfea
from conftest import EXE, SOURCE_DIR, assert_same, cantilever


def case(i):
    doc = cantilever(L=1.0 + 0.25 * i, load=(-100.0 * i, -1000.0, 10.0 * i, 0, 0, 0),
                     analyses=[{"id": "lin", "type": "linear_static"}, {"id": "K", "type": "stiffness", "node": "B"},
                               {"id": "b", "type": "buckling", "modes": 2}])
    doc["elements"][0]["divisions"] = 40 + 4 * i  # some work per case
    return doc


def test_eight_cases_on_a_thread_pool_equal_the_serial_runs():
    docs = [case(i) for i in range(1, 9)]
    serial = [beamfea.run(d) for d in docs]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(beamfea.run, docs))
    for s, t in zip(serial, threaded):
        assert_same(t, s)


def test_threads_overlap_while_the_engine_runs():
    # With the GIL held, 4 threads would take 4x one case's time even on 4 cores; released, the
    # runs overlap. Only the overlap is asserted (the machine may have few free cores): the wall
    # time of 4 concurrent runs is below the sum of their own times.
    doc = case(8)
    doc["elements"][0]["divisions"] = 400
    beamfea.run(doc)  # warm up
    with ThreadPoolExecutor(max_workers=4) as pool:
        t0 = time.perf_counter()
        res = list(pool.map(lambda _: beamfea.run(doc), range(4)))
        wall = time.perf_counter() - t0
    own = sum(sum(a["wall_time_s"] for a in r["analyses"].values()) for r in res)
    print(f"4 concurrent runs: wall {wall:.3f} s, sum of engine times {own:.3f} s")
    assert wall < 0.98 * own or os.cpu_count() == 1


def sweep_spec(base):
    return {
        "base": base,
        "grid": [{"name": "L", "pointer": "/nodes/1/xyz/0", "values": [1.0, 1.5, 2.0]},
                 {"name": "E", "pointer": "/materials/0/E", "values": [7e10, 2.1e11]}],
        "outputs": [{"name": "uy", "path": "analyses.lin.nodes.B.displacement[1]"},
                    {"name": "K", "path": "analyses.K.matrix"}],
    }


def test_sweep_columns_equal_the_program_table(tmp_path):
    base = tmp_path / "base.json"
    base.write_text(json.dumps(cantilever(analyses=[{"id": "lin", "type": "linear_static"},
                                                    {"id": "K", "type": "stiffness", "node": "B"}])))
    spec = tmp_path / "sweep.json"
    spec.write_text(json.dumps(sweep_spec("base.json")))
    subprocess.run([EXE, "sweep", str(spec), "--out", str(tmp_path / "out"), "-q"], check=True)
    with open(tmp_path / "out" / "cases.csv") as f:
        rows = list(csv.DictReader(f))
    import beamfea as bf
    cols = bf._beamfea.sweep(str(spec), 2, None)  # the dict of columns, with or without pandas
    assert list(cols) == list(rows[0].keys())
    assert len(cols["case"]) == len(rows) == 6
    for name, col in cols.items():
        if isinstance(col, np.ndarray):
            assert col.dtype == np.float64
            if name != "wall_time_s":
                np.testing.assert_array_equal(col, [float(r[name]) for r in rows], err_msg=name)
        else:
            assert col == [r[name] for r in rows], name
    # closed form on top: u_y = -P L^3 / 3EI
    P, Iz = 1000.0, 3e-6
    np.testing.assert_allclose(cols["uy"], -P * cols["L"] ** 3 / (3 * cols["E"] * Iz), rtol=1e-9)
    # the public function: a DataFrame with pandas, else the same dict
    t = beamfea.sweep(spec, jobs=2)
    assert list(t["status"]) == ["ok"] * 6


def test_sweep_from_a_dict_reports_bad_cases_as_rows(chdir_tmp):
    (chdir_tmp / "base.json").write_text(json.dumps(cantilever()))
    spec = sweep_spec("base.json")
    spec["grid"][1]["values"] = [2.1e11, -1.0]  # E < 0: bad input in half the cases
    spec["outputs"] = spec["outputs"][:1]
    cols = beamfea._beamfea.sweep(spec, 0, None)
    assert cols["status"] == ["ok", "bad input"] * 3
    assert np.isnan(cols["uy"][1::2]).all() and np.isfinite(cols["uy"][0::2]).all()
    assert all("/materials/0/E" in m for m in cols["message"][1::2])


def test_bad_sweep_raises_with_its_pointer(chdir_tmp):
    (chdir_tmp / "base.json").write_text(json.dumps(cantilever()))
    spec = sweep_spec("base.json")
    spec["grid"][0]["pointer"] = "/nodes/7/xyz/0"
    with pytest.raises(beamfea.InputError) as e:
        beamfea.sweep(spec)
    assert e.value.pointer.startswith("/grid/0")
