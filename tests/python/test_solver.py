"""The top-level "solver": beamfea.run gives the program's answers with the iterative solver and
reports which solver ran, with its computed residual ||F - K u|| / ||F||."""
import numpy as np

import beamfea
from conftest import assert_same, run_cli

RTOL = 1e-10


def portal(solver):
    """Two clamped columns and a beam (3 elements each), loaded sideways and down at one top."""
    nodes = [{"id": "A", "xyz": [0, 0, 0]}, {"id": "a", "xyz": [0, 0, 3]},
             {"id": "B", "xyz": [4, 0, 0]}, {"id": "b", "xyz": [4, 0, 3]}]
    beam = lambda i, n0, n1, o: {"id": i, "type": "beam", "nodes": [n0, n1], "material": "s", "section": "r",
                                 "orientation": o, "divisions": 3}
    return {
        "nodes": nodes,
        "materials": [{"id": "s", "E": 2.1e11, "nu": 0.3}],
        "sections": [{"id": "r", "shape": "rectangle", "b": 0.1, "h": 0.2}],
        "elements": [beam("Aa", "A", "a", [1, 0, 0]), beam("Bb", "B", "b", [1, 0, 0]), beam("ab", "a", "b", [0, 0, 1])],
        "supports": [{"node": "A", "fix": "all"}, {"node": "B", "fix": "all"}],
        "loads": [{"node": "a", "force": [5e3, 1e3, -2e4]}],
        "solver": solver,
        "analyses": [{"id": "lin", "type": "linear_static"}, {"id": "k", "type": "stiffness", "node": "b"}],
    }


def test_iterative_equals_direct_and_reports_its_solver(tmp_path):
    direct = beamfea.run(portal({"type": "direct"}))["analyses"]["lin"]
    iterative = beamfea.run(portal({"type": "iterative", "rtol": RTOL}))["analyses"]["lin"]
    assert direct["solver"]["type"] == "direct" and direct["solver"]["iterations"] == 1
    assert direct["solver"]["residual"] < 1e-13
    assert iterative["solver"]["type"] == "iterative" and iterative["solver"]["iterations"] > 1
    assert iterative["solver"]["residual"] <= RTOL
    for n in ("a", "b"):
        ud, ui = np.array(direct["nodes"][n]["displacement"]), np.array(iterative["nodes"][n]["displacement"])
        assert np.abs(ui - ud).max() < 1e-6 * np.abs(ud).max(), n
    kd = beamfea.run(portal({"type": "direct"}))["analyses"]["k"]
    ki = beamfea.run(portal({"type": "iterative", "rtol": RTOL}))["analyses"]["k"]
    assert kd["solver"]["type"] == "direct" and ki["solver"]["type"] == "iterative"
    assert ki["solver"]["residual"] <= RTOL
    assert np.abs(np.array(ki["matrix"]) - np.array(kd["matrix"])).max() < 1e-6 * np.abs(np.array(kd["matrix"])).max()
    # The program writes the same results.
    api = beamfea.run(portal({"type": "iterative", "rtol": RTOL}))
    assert_same(api["analyses"], run_cli(portal({"type": "iterative", "rtol": RTOL}), tmp_path)["analyses"])


def test_a_solve_short_of_rtol_is_a_failed_analysis_naming_the_residual():
    res = beamfea.run(portal({"type": "iterative", "rtol": RTOL, "max_iterations": 1}))["analyses"]["lin"]
    assert res["status"] == "not converged"
    assert "relative residual" in res["message"]
    assert res["solver"]["residual"] > RTOL
