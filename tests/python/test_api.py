"""The module's contract: version, NumPy conversion, files, errors, failed analyses."""
import json
import os
import re

import numpy as np
import pytest

import beamfea
from conftest import SOURCE_DIR, cantilever


def test_version_is_the_cmake_project_version():
    with open(os.path.join(SOURCE_DIR, "CMakeLists.txt")) as f:
        m = re.search(r"project\(beamfea VERSION ([0-9.]+)", f.read())
    assert beamfea.__version__ == m.group(1)
    assert beamfea.run(cantilever())["beamfea"] == beamfea.__version__


def test_blas_reports_the_kernels_and_never_leaves_a_recent_cpu_on_generic_ones():
    info = beamfea.blas()
    assert set(info) == {"openblas", "core", "replaced"}
    if not info["openblas"]:
        assert info["core"] == "" and info["replaced"] == ""
        return
    with open("/proc/cpuinfo") as f:
        flags = set(next(l for l in f if l.startswith("flags")).split())
    if "OPENBLAS_CORETYPE" not in os.environ and {"avx2", "fma"} <= flags:
        # OpenBLAS < 0.3.25 falls back to Prescott on Intel models it does not know (app/openblas.hpp).
        assert info["core"].lower() != "prescott"
    if info["replaced"]:
        assert info["replaced"].lower() == "prescott"


def test_arrays_are_float64_ndarrays_of_the_right_shapes():
    doc = cantilever(analyses=[{"id": "lin", "type": "linear_static"}, {"id": "K", "type": "stiffness", "node": "B"}])
    doc["elements"][0]["divisions"] = 3
    res = beamfea.run(doc)
    lin = res["analyses"]["lin"]
    for node in ("A", "B"):
        d = lin["nodes"][node]["displacement"]
        assert isinstance(d, np.ndarray) and d.dtype == np.float64 and d.shape == (6,)
    assert lin["nodes"]["A"]["reaction"].shape == (6,)
    ef = lin["elements"]["e"]["end_forces"]
    assert isinstance(ef, np.ndarray) and ef.dtype == np.float64 and ef.shape == (2, 6)
    K = res["analyses"]["K"]["matrix"]
    assert K.shape == (6, 6) and K.dtype == np.float64
    np.testing.assert_allclose(K, K.T, rtol=1e-12, atol=1e-9 * np.abs(K).max())
    # scalars stay Python scalars, strings str
    assert isinstance(lin["status"], str) and lin["status"] == "ok"
    assert isinstance(res["model"]["nodes"], int)
    assert isinstance(res["analyses"]["K"]["length_scale"], float)


def test_numpy_input_is_accepted():
    doc = cantilever()
    doc["nodes"][1]["xyz"] = np.array([2.0, 0.0, 0.0])
    doc["materials"][0]["E"] = np.float64(2.1e11)
    doc["elements"][0]["divisions"] = np.int64(2)
    plain = cantilever()
    plain["elements"][0]["divisions"] = 2
    ref, got = beamfea.run(plain), beamfea.run(doc)
    np.testing.assert_array_equal(got["analyses"]["lin"]["nodes"]["B"]["displacement"],
                                  ref["analyses"]["lin"]["nodes"]["B"]["displacement"])


def test_no_file_is_written_without_out(chdir_tmp):
    before = set(os.listdir(chdir_tmp))
    beamfea.run(cantilever())
    beamfea.check(cantilever())
    assert set(os.listdir(chdir_tmp)) == before


def test_out_writes_results_and_vtk(tmp_path):
    res = beamfea.run(cantilever(), out=tmp_path / "o")
    files = sorted(os.listdir(tmp_path / "o"))
    assert "results.json" in files and "lin.vtu" in files
    with open(tmp_path / "o" / "results.json") as f:
        disk = json.load(f)
    assert disk["analyses"]["lin"]["nodes"]["B"]["displacement"] == res["analyses"]["lin"]["nodes"]["B"]["displacement"].tolist()


def test_model_from_a_path(tmp_path):
    p = tmp_path / "m.json"
    p.write_text(json.dumps(cantilever()))
    a, b = beamfea.run(p), beamfea.run(str(p))
    np.testing.assert_array_equal(a["analyses"]["lin"]["nodes"]["B"]["displacement"],
                                  b["analyses"]["lin"]["nodes"]["B"]["displacement"])
    assert beamfea.check(p) == {"nodes": 2, "elements": 1, "members": 1, "joints": 0}


def test_analyses_selects_by_id_or_replaces_the_specs():
    doc = cantilever(analyses=[{"id": "lin", "type": "linear_static"}, {"id": "K", "type": "stiffness", "node": "B"}])
    assert list(beamfea.run(doc, analyses="K")["analyses"]) == ["K"]
    assert list(beamfea.run(doc, analyses=["lin"])["analyses"]) == ["lin"]
    res = beamfea.run(doc, analyses=[{"id": "b", "type": "buckling", "modes": 1}])
    assert list(res["analyses"]) == ["b"]
    with pytest.raises(beamfea.InputError, match="no analysis with id 'nope'"):
        beamfea.run(doc, analyses="nope")


def test_bad_input_names_the_json_pointer_and_the_entity():
    doc = cantilever()
    doc["elements"][0]["nodes"][1] = "Z"
    with pytest.raises(beamfea.InputError) as e:
        beamfea.run(doc)
    assert e.value.pointer == "/elements/0/nodes/1"
    assert e.value.entity == "element 'e'"
    assert "unknown node 'Z'" in str(e.value)
    assert isinstance(e.value, ValueError) and isinstance(e.value, beamfea.Error)
    with pytest.raises(beamfea.InputError) as e:
        beamfea.check(doc)
    assert e.value.pointer == "/elements/0/nodes/1"


def test_bad_analysis_spec_points_into_analyses():
    doc = cantilever(analyses=[{"id": "K", "type": "stiffness", "node": "nowhere"}])
    with pytest.raises(beamfea.InputError) as e:
        beamfea.run(doc)
    assert e.value.pointer == "/analyses/0/node" and e.value.entity == "analysis 'K'"


def test_python_values_that_are_not_json_are_input_errors():
    doc = cantilever()
    doc["materials"][0]["E"] = float("nan")
    with pytest.raises(beamfea.InputError) as e:
        beamfea.run(doc)
    assert e.value.pointer == "/materials/0/E" and e.value.entity == "material 'm'"
    doc = cantilever()
    doc["nodes"][0]["xyz"] = {1, 2, 3}
    with pytest.raises(beamfea.InputError) as e:
        beamfea.run(doc)
    assert e.value.pointer == "/nodes/0/xyz" and "set" in str(e.value)


def test_missing_file_and_malformed_json_are_input_errors(tmp_path):
    with pytest.raises(beamfea.InputError):
        beamfea.run(tmp_path / "absent.json")
    p = tmp_path / "bad.json"
    p.write_text('{"nodes": [}')
    with pytest.raises(beamfea.InputError, match="malformed JSON"):
        beamfea.run(p)


def test_a_failed_analysis_is_a_result_with_its_status():
    doc = cantilever()
    doc["supports"] = []  # a free-floating beam: a mechanism
    res = beamfea.run(doc)
    lin = res["analyses"]["lin"]
    assert lin["status"] == "mechanism"
    assert "message" in lin and lin["message"]


def test_help_says_what_run_returns():
    doc = beamfea.run.__doc__
    assert "Returns:" in doc and "results.json" in doc and "ndarray" in doc
    assert "Raises:" in doc and "InputError" in doc


def test_type_stubs_declare_the_public_api():
    import ast
    import inspect
    stub = os.path.join(os.path.dirname(beamfea.__file__), "__init__.pyi")
    tree = ast.parse(open(stub).read())
    declared = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    declared |= {t.id for n in tree.body if isinstance(n, ast.AnnAssign) for t in [n.target]}
    assert set(beamfea.__all__) <= declared
    # the stub's parameters are the function's
    for fn in ("run", "check", "sweep"):
        stub_fn = next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == fn)
        stub_args = [a.arg for a in stub_fn.args.args + stub_fn.args.kwonlyargs]
        assert stub_args == list(inspect.signature(getattr(beamfea, fn)).parameters), fn


def test_a_model_that_contains_itself_is_an_input_error_not_a_crash():
    doc = cantilever()
    doc["_note"] = [doc]
    with pytest.raises(beamfea.InputError, match="contain itself"):
        beamfea.run(doc)
