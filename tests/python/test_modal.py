"""Modal analysis through the Python module, against closed forms."""
import math

import numpy as np
import pytest

import beamfea
from conftest import cantilever

L, E, G, A, IY, IZ, J = 2.0, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6


def test_point_mass_on_a_massless_cantilever():
    # Blevins, Formulas for Natural Frequency and Mode Shape (1979), Table 6-2: a tip mass m on a
    # massless cantilever, f = sqrt(3 E I / (m L^3)) / (2 pi) in each bending plane (one Hermite
    # element is exact in statics), and the axial mode sqrt(E A / (m L)) / (2 pi). Exactly three
    # finite modes: the mass has no rotary inertia.
    m = 25.0
    doc = cantilever(analyses=[{"id": "m", "type": "modal", "modes": 3}])
    doc["masses"] = [{"node": "B", "mass": m}]
    res = beamfea.run(doc)["analyses"]["m"]
    assert res["status"] == "ok"
    f = np.asarray(res["frequencies"], dtype=float)
    expect = sorted([math.sqrt(3 * E * IY / (m * L**3)), math.sqrt(3 * E * IZ / (m * L**3)),
                     math.sqrt(E * A / (m * L))])
    assert f.shape == (3,)
    for got, w in zip(f, expect):
        assert got == pytest.approx(w / (2 * math.pi), rel=1e-9)
    assert list(res["kinds"]) == ["elastic"] * 3
    # the effective mass of the first mode (bending in z, Iy < Iz) is the whole mass, along z
    assert res["effective_mass"]["uz"][0] == pytest.approx(m, rel=1e-9)


def test_cantilever_with_distributed_mass_converges_to_beta_L():
    # Blevins (1979), Table 8-1: omega_1 = (1.87510407)^2 sqrt(E I / (rho A L^4)) (Euler-Bernoulli,
    # no rotary inertia); 16 elements of the consistent mass: error ~1.3e-7 (h^4;
    # tests/solvers/modal_test.cpp), asserted 1e-6. A slender section (radius of gyration 3e-4 m,
    # L = 2 m) keeps the rotary inertia's lowering below 1e-7; the default section's (r/L = 0.02)
    # lowers the first frequency by 1.2e-3.
    rho, iy, iz = 7850.0, 1e-10, 2e-10
    doc = cantilever(Iy=iy, Iz=iz, analyses=[{"id": "m", "type": "modal", "modes": 2}])
    doc["materials"][0]["density"] = rho
    doc["elements"][0]["divisions"] = 16
    doc["loads"] = []
    res = beamfea.run(doc)["analyses"]["m"]
    f = np.asarray(res["frequencies"], dtype=float)
    beta = 1.87510407
    for k, inertia in enumerate((iy, iz)):
        exact = beta**2 * math.sqrt(E * inertia / (rho * A * L**4)) / (2 * math.pi)
        assert f[k] == pytest.approx(exact, rel=1e-6)


def test_iterative_solver_gives_the_direct_frequencies_and_says_so():
    # "solver": {"type": "iterative"}: SLEPc's Krylov-Schur with shift-and-invert. The same first
    # frequency as the direct solver (and Blevins' beta L = 1.87510407, 16 elements: 1e-6), a
    # "solver" report with its iterations and the computed eigen-residual; a buckling analysis of
    # the same model on SLEPc gives Euler's pi^2 E I / (4 L^2) (16 elements: 1e-6).
    rho, iy, iz, P = 7850.0, 1e-10, 2e-10, 1.0
    doc = cantilever(Iy=iy, Iz=iz, analyses=[{"id": "m", "type": "modal", "modes": 4},
                                             {"id": "b", "type": "buckling", "modes": 2}])
    doc["materials"][0]["density"] = rho
    doc["elements"][0]["divisions"] = 16
    doc["loads"] = [{"node": "B", "force": [-P, 0, 0]}]
    direct = beamfea.run({**doc, "solver": {"type": "direct"}})["analyses"]
    iterative = beamfea.run({**doc, "solver": {"type": "iterative", "rtol": 1e-10}})["analyses"]
    assert direct["m"]["solver"]["type"] == "direct"
    assert direct["m"]["solver"]["iterations"] == 1
    solver = iterative["m"]["solver"]
    assert solver["type"] == "iterative"
    assert solver["iterations"] >= 1
    assert 0 <= solver["residual"] < 1e-8
    fd = np.asarray(direct["m"]["frequencies"], dtype=float)
    fi = np.asarray(iterative["m"]["frequencies"], dtype=float)
    np.testing.assert_allclose(fi, fd, rtol=1e-8)
    exact = 1.87510407**2 * math.sqrt(E * iy / (rho * A * L**4)) / (2 * math.pi)
    assert fi[0] == pytest.approx(exact, rel=1e-6)
    assert iterative["b"]["solver"]["type"] == "iterative"
    euler = math.pi**2 * E * iy / (4 * L**2)
    assert iterative["b"]["load_factors"][0] * P == pytest.approx(euler, rel=1e-6)
