"""The examples that use the Python module run (in their quick modes), and where they keep the
program's path, both paths give the same numbers."""
import csv
import json
import os
import subprocess
import sys

import pytest

from conftest import EXE, SOURCE_DIR

EX = os.path.join(SOURCE_DIR, "examples")


def run(args, **kw):
    env = dict(os.environ, MPLBACKEND="Agg")
    p = subprocess.run([sys.executable] + args, capture_output=True, text=True, env=env, **kw)
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


def test_07_five_bar_stiffness_map(tmp_path):
    out = run([os.path.join(EX, "07_python_workspace_stiffness", "five_bar.py"), "--quick", "--out", str(tmp_path)])
    assert "must be <= 1" in out and "(0 failed)" in out
    assert os.path.exists(tmp_path / "stiffness_map.png")


def test_03_workspace_map_in_process(tmp_path):
    out = run([os.path.join(EX, "03_workspace_stiffness_map", "plot.py"), "--quick", "--png", str(tmp_path / "m.png")])
    assert "cases ok" in out and os.path.exists(tmp_path / "m.png")


def test_02_bu_in_process_equals_the_program(tmp_path):
    script = os.path.join(EX, "02_bu_planar_manipulator", "bu_example.py")
    run([script, "--no-plots", "--out", str(tmp_path / "api")])
    run([script, "--no-plots", "--out", str(tmp_path / "cli"), "--beamfea", EXE])
    a = json.loads((tmp_path / "api" / "tables.json").read_text())
    c = json.loads((tmp_path / "cli" / "tables.json").read_text())
    assert a == c
    assert (tmp_path / "api" / "tables.md").read_text() == (tmp_path / "cli" / "tables.md").read_text()


def test_compare_models_both_engines_give_the_same_report(tmp_path):
    # scripts/compare_models.py on two of example 05's lumped models (the beam models take a
    # minute each): in process and with the program, the same summary; and the closed forms of
    # model A (rigid links on actuator springs K_theta = 1, L = 1; examples/05 README):
    # straight chain buckles at P = K_theta / L = 1, the Pi posture's unloaded stiffness is 2.
    models = os.path.join(EX, "05_pashkevich_chain", "models")
    with open(os.path.join(EX, "05_pashkevich_chain", "comparison_spec.json")) as f:
        spec = json.load(f)
    spec["pairs"] = [{"id": p, "name": p, "models": [{"key": "lumped", "file": os.path.join(models, f"{p}_lumped.json")}]}
                     for p in ("A_S", "A_Pi")]
    (tmp_path / "spec.json").write_text(json.dumps(spec))
    script = os.path.join(SOURCE_DIR, "scripts", "compare_models.py")
    for name, extra in (("api", []), ("cli", ["--beamfea", EXE])):
        run([script, str(tmp_path / "spec.json"), "--out", str(tmp_path / name), "--no-plots"] + extra)
    rows = {}
    for name in ("api", "cli"):
        with open(tmp_path / name / "summary.csv") as f:
            rows[name] = list(csv.DictReader(f))
    assert rows["api"] == rows["cli"]
    value = {(r["pair"], r["quantity"]): r["lumped"] for r in rows["api"]}
    assert float(value[("A_S", "buckling_load")]) == pytest.approx(1.0, rel=1e-9)
    assert float(value[("A_S", "critical_force")]) == pytest.approx(1.0, rel=1e-5)
    assert float(value[("A_Pi", "unloaded")]) == pytest.approx(2.0, rel=1e-9)
    assert (tmp_path / "api" / "A_S" / "lumped" / "results.json").exists()  # beamfea's files


def test_05_report_critical_force_in_process(tmp_path):
    sys.path.insert(0, os.path.join(EX, "05_pashkevich_chain"))
    import report
    f = os.path.join(EX, "05_pashkevich_chain", "models", "A_S_lumped.json")
    v, how = report.critical_force(None, f, str(tmp_path / "api"), lambda s: None)
    assert how == "buckling" and v == pytest.approx(1.0, rel=1e-9)
    w, _ = report.critical_force(EXE, f, str(tmp_path / "cli"), lambda s: None)
    assert v == w


def test_11_bu_platform_poses(tmp_path):
    """The 3-RRR driven by platform targets: the example exits 1 when the solved joint coordinates
    miss the closed-form inverse kinematics or the compliance misses J K^-1 J^T."""
    out = run([os.path.join(EX, "11_bu_platform_poses", "platform_poses.py"), "--no-plots"])
    assert out.count("| J1J2J3 | P") == 5 and out.count("| J1J2J6 | P") == 5


def test_08_workspace_error_map_in_process_equals_the_program(tmp_path):
    """The five-bar's generated lumped model against its beam model over a 3 x 3 grid of end-point
    positions (scripts/compare_workspace.py): the example exits 1 when the unloaded compliances
    differ by more than 1e-9 (condensation of a rod meeting the rest at its ends is exact); in
    process and with the program the same table."""
    script = os.path.join(EX, "08_five_bar_lumped_vs_beam", "workspace_map.py")
    rows = {}
    for name, extra in (("api", []), ("cli", ["--beamfea", EXE, "--no-plots"])):
        out = run([script, "--quick", "--out", str(tmp_path / name)] + extra)
        assert "9 of 9 poses in both models" in out
        with open(tmp_path / name / "workspace.csv") as f:
            rows[name] = list(csv.DictReader(f))
    assert len(rows["api"]) == 9 and os.path.exists(tmp_path / "api" / "workspace.png")
    for a, c in zip(rows["api"], rows["cli"]):
        assert a["pose"] == c["pose"]
        for k in ("k0_1_beam", "kL_1_lumped", "lambda_beam", "lambda_lumped"):
            assert float(a[k]) == pytest.approx(float(c[k]), rel=1e-5)  # the CSV's 6 digits
        # the loaded compliance differs at first order in the load, the unloaded one does not
        assert float(a["dCL_t_lumped"]) > 1e3 * float(a["dC0_t_lumped"])
