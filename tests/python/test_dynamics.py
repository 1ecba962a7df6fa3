"""Damping, frequency response and transient response through the Python module, against the
single-DOF closed forms."""
import math

import numpy as np
import pytest

import beamfea

K, M, C = 1.0e4, 1.0, 2.0  # omega_n = 100 rad/s, zeta = C / (2 sqrt(K M)) = 0.01


def oscillator(analyses):
    """A mass (with rotary inertia) on a virtual spring with joint damping: six oscillators."""
    return {
        "nodes": [{"id": "A", "xyz": [0, 0, 0]}, {"id": "B", "xyz": [0, 0, 0]}],
        "joints": [{"id": "v", "type": "virtual_spring", "nodes": ["A", "B"],
                    "axes": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "stiffness": [K] * 6, "damping": [C] * 6}],
        "supports": [{"node": "A", "fix": "all"}],
        "masses": [{"node": "B", "mass": M, "inertia": [[M, 0, 0], [0, M, 0], [0, 0, M]]}],
        "loads": [{"node": "B", "force": [0, 5.0, 0]}],
        "analyses": analyses,
    }


def test_frf_is_the_single_dof_receptance_as_numpy_arrays():
    # |H| = 1 / sqrt((k - m w^2)^2 + (c w)^2), phase = -atan2(c w, k - m w^2).
    frf = {"id": "h", "type": "frf", "input": {"node": "B", "dof": "uy"}, "outputs": [{"node": "B", "dof": "uy"}],
           "frequencies": {"from": 1.0, "to": 100.0, "count": 201, "spacing": "log"}}
    res = beamfea.run(oscillator([frf]))["analyses"]["h"]
    assert res["status"] == "ok"
    hz = res["frequencies"]
    assert isinstance(hz, np.ndarray) and hz.shape == (201,)
    assert hz[100] == pytest.approx(10.0, rel=1e-12)
    out = res["outputs"][0]
    w = 2 * math.pi * hz
    mag = 1.0 / np.hypot(K - M * w**2, C * w)
    np.testing.assert_allclose(out["magnitude"], mag, rtol=1e-9)
    np.testing.assert_allclose(np.radians(out["phase_deg"]), -np.arctan2(C * w, K - M * w**2), atol=1e-9)
    np.testing.assert_allclose(np.asarray(out["real"]) + 1j * np.asarray(out["imag"]), 1.0 / (K - M * w**2 + 1j * C * w), rtol=1e-9)


def test_transient_step_is_the_closed_form_as_time_series():
    # x(t) = x_st (1 - e^{-zeta w t} (cos w_d t + zeta / sqrt(1 - zeta^2) sin w_d t)), x_st = F / k.
    tr = {"id": "t", "type": "transient", "dt": 2e-4, "duration": 0.2, "track": ["B"], "output_every": 1,
          "loads": [{"time_function": {"type": "step"}}]}
    res = beamfea.run(oscillator([tr]))["analyses"]["t"]
    assert res["status"] == "ok"
    t = np.array([s["time"] for s in res["steps"]])
    y = np.array([s["nodes"]["B"]["displacement"][1] for s in res["steps"]])
    w = math.sqrt(K / M)
    zeta = C / (2 * math.sqrt(K * M))
    wd = w * math.sqrt(1 - zeta**2)
    xst = 5.0 / K
    x = xst * (1 - np.exp(-zeta * w * t) * (np.cos(wd * t) + zeta / math.sqrt(1 - zeta**2) * np.sin(wd * t)))
    np.testing.assert_allclose(y, x, atol=1e-3 * xst)
    e = res["steps"][-1]["energy"]
    assert e["kinetic"] + e["strain"] + e["dissipated"] == pytest.approx(e["work"], rel=1e-10)
    assert res["peaks"]["B"]["peak_displacement"] == pytest.approx(xst * (1 + math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2))), rel=1e-3)


def test_bad_time_function_is_an_input_error_with_its_pointer():
    tr = {"id": "t", "type": "transient", "dt": 1e-3, "duration": 0.01,
          "loads": [{"time_function": {"type": "impulse"}}]}
    with pytest.raises(beamfea.InputError) as err:
        beamfea.run(oscillator([tr]))
    assert err.value.pointer == "/analyses/0/loads/0/time_function/type"
