"""The engine's warnings (beamfea.BeamfeaWarning, results.json's "warnings", the program's
"beamfea: warning: ..." lines), progress callbacks, and Ctrl-C during a run or a sweep."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
import warnings

import numpy as np
import pytest

import beamfea
from conftest import EXE, SOURCE_DIR, cantilever, run_cli

# Ctrl-C must stop a run within a second; a sanitized build runs several times slower.
INTERRUPT_LIMIT_S = 2.0 if os.environ.get("LD_PRELOAD") else 1.0


def engine_warnings(model, **kw):
    """beamfea.run's result and the messages of the BeamfeaWarnings it raised."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = beamfea.run(model, **kw)
    return res, [str(w.message) for w in caught if issubclass(w.category, beamfea.BeamfeaWarning)]


def test_beamfea_warning_is_a_user_warning():
    assert issubclass(beamfea.BeamfeaWarning, UserWarning)


def test_a_clean_model_warns_nothing(tmp_path):
    res, raised = engine_warnings(cantilever())
    assert raised == [] and res["warnings"] == []
    assert run_cli(cantilever(), tmp_path)["warnings"] == []


def test_unused_material_and_section_warn_in_python_results_and_the_program(tmp_path):
    doc = cantilever()
    doc["materials"].append({"id": "steel2", "E": 2e11, "G": 8e10})
    doc["sections"].append({"id": "s_unused", "A": 1e-3, "Iy": 1e-6, "Iz": 1e-6, "J": 1e-6})
    res, raised = engine_warnings(doc)
    assert raised == res["warnings"]
    assert any("material 'steel2'" in w and "never used" in w for w in raised), raised
    assert any("section 's_unused'" in w and "never used" in w for w in raised), raised
    # The program: the same lines in results.json and on stderr.
    (tmp_path / "m.json").write_text(json.dumps(doc))
    p = subprocess.run([EXE, "run", str(tmp_path / "m.json"), "--out", str(tmp_path / "o"), "--no-vtk", "-q"],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert json.loads((tmp_path / "o" / "results.json").read_text())["warnings"] == raised
    for w in raised:
        assert f"beamfea: warning: {w}" in p.stderr.splitlines()
    # `check` prints the model's warnings too.
    p = subprocess.run([EXE, "check", str(tmp_path / "m.json")], capture_output=True, text=True)
    assert p.returncode == 0 and p.stderr.count("beamfea: warning: ") == 2, p.stderr


def test_many_unused_ids_make_one_line():
    doc = cantilever()
    doc["materials"] += [{"id": f"x{i}", "E": 1.0, "G": 1.0} for i in range(10)]
    _, raised = engine_warnings(doc)
    assert len(raised) == 1 and raised[0].startswith("materials 'x0', 'x1'") and "'x7' and 2 more are" in raised[0], raised


def test_a_load_on_a_fully_supported_lonely_node_warns_and_goes_into_its_reaction():
    doc = cantilever()
    doc["nodes"].append({"id": "C", "xyz": [5, 0, 0]})
    doc["supports"].append({"node": "C", "fix": "all"})
    doc["loads"].append({"node": "C", "force": [3.0, -4.0, 5.0]})
    res, raised = engine_warnings(doc)
    assert any("node 'C' is connected to nothing" in w for w in raised), raised
    assert any("load case 'default'" in w and "node 'C'" in w and "every DOF is supported" in w for w in raised), raised
    # Statics of a lone fixed node: its reaction is minus the load.
    np.testing.assert_allclose(res["analyses"]["lin"]["nodes"]["C"]["reaction"][:3], [-3.0, 4.0, -5.0], rtol=1e-12)


def test_a_path_that_uses_up_max_steps_warns():
    doc = cantilever(analyses=[{"id": "p", "type": "path", "max_steps": 3,
                                "control": {"load_factor": 1.0, "increments": 10}}])
    res, raised = engine_warnings(doc)
    assert res["analyses"]["p"]["completed"] is False
    assert any("analysis 'p'" in w and "max_steps (3)" in w for w in raised), raised


def two_bar(E1, E2):
    """Two collinear beams A-B-C, fixed at A, of moduli E1 and E2, loaded at C."""
    doc = cantilever(L=1.0)
    doc["nodes"].append({"id": "C", "xyz": [2.0, 0, 0]})
    doc["materials"] = [{"id": "m1", "E": E1, "G": E1 / 2.6}, {"id": "m2", "E": E2, "G": E2 / 2.6}]
    doc["elements"] = [
        {"id": "e1", "type": "beam", "nodes": ["A", "B"], "material": "m1", "section": "s", "orientation": [0, 0, 1]},
        {"id": "e2", "type": "beam", "nodes": ["B", "C"], "material": "m2", "section": "s", "orientation": [0, 0, 1]}]
    doc["loads"] = [{"node": "C", "force": [1.0, 0, 0]}]
    return doc


def test_an_ill_conditioned_stiffness_warns_with_its_condition_estimate():
    # A soft bar carrying a stiff one: the Jacobi-scaled stiffness of the axial DOFs is
    # [[1, -c], [-c, 1]] with c^2 = k2 / (k1 + k2), whose Cholesky factor gives the estimate
    # (L22 / L11)^2 = 1 - c^2 = k1 / (k1 + k2) = 1e-12 here (bending adds DOFs of the same kind).
    res, raised = engine_warnings(two_bar(1.0, 1e12))
    ill = [w for w in raised if "ill-conditioned" in w]
    assert len(ill) == 1, raised
    estimate = float(ill[0].split("estimate ")[1].split(" ")[0])
    assert 1e-14 < estimate <= 1.01e-12, ill[0]
    # The answer is as doubtful as the warning says: the tip's axial displacement P L (1/E1 + 1/E2) / A
    # is off by about eps / rcond (here 1e-4), within ten times that bound.
    exact = 1.0 * 1.0 * (1 / 1.0 + 1 / 1e12) / 1e-3
    error = abs(res["analyses"]["lin"]["nodes"]["C"]["displacement"][0] / exact - 1)
    assert error <= 10 * np.finfo(float).eps / estimate, (error, estimate)
    # Moduli 1e3 apart: a well-posed problem, no warning.
    _, raised = engine_warnings(two_bar(2e8, 2e11))
    assert not any("ill-conditioned" in w for w in raised), raised


def test_redundant_closure_rows_of_a_planar_loop_warn():
    with open(os.path.join(SOURCE_DIR, "examples", "08_five_bar_lumped_vs_beam", "models", "lumped.json")) as f:
        doc = json.load(f)
    doc["analyses"] = [{"id": "lin", "type": "linear_static"}]
    res, raised = engine_warnings(doc)
    rows = res["analyses"]["lin"]["statically_indeterminate"]
    # A planar loop of rigid links on parallel revolute axes: 6 closure rows, 3 of them out of plane.
    assert len(rows) == 3
    assert any(f"analysis 'lin': 3 constraint rows are redundant" in w and rows[0] in w for w in raised), raised


def long_path(steps=100000, elements=40):
    """A cantilever of `elements` beams followed in tiny load steps: minutes of steps, which the
    tests stop long before the end."""
    doc = cantilever(analyses=[{"id": "p", "type": "path", "max_steps": steps,
                                "control": {"load_factor": 1.0, "increments": steps}}])
    doc["nodes"] = [{"id": "A" if i == 0 else ("B" if i == elements else f"n{i}"), "xyz": [2.0 * i / elements, 0, 0]}
                    for i in range(elements + 1)]
    doc["elements"] = [{"id": f"e{i}", "type": "beam", "nodes": [doc["nodes"][i]["id"], doc["nodes"][i + 1]["id"]],
                        "material": "m", "section": "s", "orientation": [0, 0, 1]} for i in range(elements)]
    return doc


def test_progress_is_called_with_counts_and_the_engine_lines():
    calls = []
    beamfea.run(cantilever(analyses=[{"id": "lin", "type": "linear_static"},
                                     {"id": "p", "type": "path", "control": {"load_factor": 1.0, "increments": 5}}]),
                progress=lambda *a: calls.append(a))
    assert calls, "progress never called"
    assert all(len(c) == 3 and isinstance(c[0], int) and isinstance(c[1], int) and isinstance(c[2], str) for c in calls)
    assert calls[-1][:2] == (2, 2)
    # A sweep's progress counts its cases.
    calls.clear()
    spec = {"model": cantilever(), "grid": [{"name": "L", "pointer": "/nodes/1/xyz/0", "values": [1.0, 2.0, 3.0]}],
            "outputs": [{"name": "uy", "path": "analyses.lin.nodes.B.displacement[1]"}]}
    beamfea.sweep(spec, jobs=1, progress=lambda *a: calls.append(a))
    assert calls[-1][:2] == (3, 3)


def test_progress_is_called_at_least_once_a_second_on_a_long_run():
    times = []
    def cb(done, total, message):
        times.append(time.monotonic())
        if times[-1] - times[0] > 3.0:
            raise RuntimeError("enough")  # an exception of the callback stops the run
    with pytest.raises(RuntimeError, match="enough"):
        beamfea.run(long_path(), progress=cb)
    gaps = np.diff(times)
    assert len(times) >= 4 and gaps.max() < 1.2, gaps


def test_the_pandas_return_path_of_a_sweep():
    pandas = pytest.importorskip("pandas", reason="pandas is optional (Debian's python3-pandas)")
    spec = {"model": cantilever(), "grid": [{"name": "L", "pointer": "/nodes/1/xyz/0", "values": [1.0, 2.0]}],
            "outputs": [{"name": "uy", "path": "analyses.lin.nodes.B.displacement[1]"}]}
    t = beamfea.sweep(spec, jobs=1)
    assert isinstance(t, pandas.DataFrame)
    assert list(t.columns) == ["case", "L", "uy", "status", "message", "wall_time_s"]
    # u_y = -P L^3 / (3 E Iz) (cantilever's defaults: P = 1000, E = 2.1e11, Iz = 3e-6)
    np.testing.assert_allclose(t["uy"].to_numpy(), -1000.0 * t["L"].to_numpy() ** 3 / (3 * 2.1e11 * 3e-6), rtol=1e-9)
    assert t["uy"].dtype == np.float64 and list(t["status"]) == ["ok", "ok"]


CHILD = textwrap.dedent("""
    import json, sys, time, beamfea
    kind, out = sys.argv[1], sys.argv[2]
    doc = json.loads(sys.stdin.read())
    started = []
    def progress(done, total, message):
        if not started:
            started.append(1)
            print("started", flush=True)
    try:
        if kind == "sweep":
            beamfea.sweep(doc, jobs=1, progress=progress)
        else:
            beamfea.run(doc, out=out, progress=progress)
        print("finished", flush=True)
    except KeyboardInterrupt:
        print("KeyboardInterrupt", time.monotonic(), flush=True)
        # The interpreter stays usable: the engine runs again.
        r = beamfea.run(doc["model"] if kind == "sweep" else doc, analyses=[{"id": "lin", "type": "linear_static"}])
        print("usable", r["analyses"]["lin"]["status"], flush=True)
""")


def interrupt(tmp_path, kind, doc):
    """Runs CHILD, sends SIGINT once the engine reports progress; returns its stdout lines and the
    seconds from the signal to its KeyboardInterrupt."""
    env = dict(os.environ)
    p = subprocess.Popen([sys.executable, "-c", CHILD, kind, str(tmp_path / "out")], stdin=subprocess.PIPE,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    p.stdin.write(json.dumps(doc))
    p.stdin.close()
    assert p.stdout.readline().strip() == "started"
    time.sleep(0.3)  # well inside the run
    t0 = time.monotonic()
    p.send_signal(signal.SIGINT)
    lines = p.stdout.read().split("\n")
    p.wait(timeout=60)
    assert lines[0].startswith("KeyboardInterrupt"), (lines, p.stderr.read())
    return lines, float(lines[0].split()[1]) - t0


def test_ctrl_c_stops_a_long_sweep_within_a_second(tmp_path):
    spec = {"model": cantilever(), "grid": [{"name": "L", "pointer": "/nodes/1/xyz/0",
                                             "values": [1.0 + i * 1e-6 for i in range(200000)]}],
            "outputs": [{"name": "uy", "path": "analyses.lin.nodes.B.displacement[1]"}]}
    lines, dt = interrupt(tmp_path, "sweep", spec)
    assert dt < INTERRUPT_LIMIT_S, dt
    assert lines[1] == "usable ok"


def test_ctrl_c_stops_a_long_path_within_a_second_and_writes_nothing(tmp_path):
    lines, dt = interrupt(tmp_path, "run", long_path())
    assert dt < INTERRUPT_LIMIT_S, dt
    assert lines[1] == "usable ok"
    # No results.json, no staged file: the output folder is not there at all (it was made by the run).
    assert not (tmp_path / "out").exists(), list((tmp_path / "out").rglob("*"))
