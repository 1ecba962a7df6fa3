"""Second-order statics and tension-only members through beamfea.run: iterations, amplification
and inactive_members, against closed forms, and the same answers as the program."""
import math

import pytest

import beamfea
from conftest import assert_same, cantilever, run_cli

L, E, IY, IZ = 2.0, 2.1e11, 2e-6, 3e-6  # conftest.cantilever's section
P_CR = math.pi**2 * E * IZ / (4 * L**2)  # Euler's cantilever, bending in x-y (Timoshenko & Gere eq. 2.3)
P_CR_WEAK = math.pi**2 * E * IY / (4 * L**2)  # the same in x-z, the lower one


def column(P, H, analysis):
    doc = cantilever(load=(-P, H, 0, 0, 0, 0), analyses=[analysis])
    doc["elements"][0]["divisions"] = 16
    return doc


def test_second_order_returns_iterations_and_amplification(tmp_path):
    # Below both Euler loads (P = 0.6 of the weak one). Beam-column with a lateral end load: tip = H (tan kL - kL) / (k^3 EI), k = sqrt(P / EI)
    # (Timoshenko & Gere, Theory of Elastic Stability, sec. 1.7); linear tip H L^3 / (3 EI).
    P, H = 0.4 * P_CR, 500.0
    doc = column(P, H, {"id": "pd", "type": "second_order"})
    res = beamfea.run(doc)["analyses"]["pd"]
    k = math.sqrt(P / (E * IZ))
    tip = H * (math.tan(k * L) - k * L) / (k**3 * E * IZ)
    assert res["status"] == "ok"
    assert res["nodes"]["B"]["displacement"][1] == pytest.approx(tip, rel=1e-5)
    assert res["amplification"] == pytest.approx(tip / (H * L**3 / (3 * E * IZ)), rel=1e-5)
    assert res["iterations"] >= 1
    assert len(res["inactive_members"]) == 0
    assert_same(beamfea.run(doc), run_cli(doc, tmp_path))


def test_diverged_second_order_is_a_failed_result_not_an_exception():
    P = 1.6 * P_CR
    res = beamfea.run(column(P, 100.0, {"id": "pd", "type": "second_order"}))["analyses"]["pd"]
    assert res["status"] == "failed"
    assert "second-order analysis diverged: load above the critical load factor" in res["message"]
    assert res["critical_load_factor"] == pytest.approx(P_CR_WEAK / P, rel=1e-4)


def test_linear_static_names_inactive_members():
    # A compression-only strut pulled: it goes slack; a spring-free tip then is a mechanism.
    doc = cantilever(load=(1000.0, 0, 0, 0, 0, 0))
    doc["elements"][0]["behaviour"] = "compression_only"
    res = beamfea.run(doc)["analyses"]["lin"]
    assert res["status"] == "mechanism"
    assert res["inactive_members"] == ["e"]
    doc["elements"][0]["behaviour"] = "tension_only"
    res = beamfea.run(doc)["analyses"]["lin"]
    assert res["status"] == "ok"
    assert len(res["inactive_members"]) == 0
    assert res["nodes"]["B"]["displacement"][0] == pytest.approx(1000.0 * L / (E * 1e-3), rel=1e-9)
