"""Section shapes from Python and in a model: beamfea.section_properties and a beam on an "i" shape."""
import json
import subprocess

import pytest

import beamfea
from conftest import EXE, cantilever


def test_every_listed_shape_computes_and_the_program_lists_the_same_shapes():
    shapes = beamfea.section_shapes()
    names = [s["shape"] for s in shapes]
    assert names == ["rectangle", "circle", "tube", "i", "channel", "tee", "angle", "box"]
    listing = subprocess.run([EXE, "sections"], capture_output=True, text=True, check=True).stdout
    for s in shapes:
        assert f"\n{s['shape']}: " in listing


def test_an_i_section_in_a_model_bends_with_the_plates_second_moment():
    # Cantilever of an I (h along local z = global z): a tip load along -z bends it about y, tip
    # deflection P L^3 / (3 E Iy) with Iy of the three plates written out here.
    h, b, tw, tf = 0.3, 0.15, 0.0071, 0.0107
    Iy = (b * h**3 - (b - tw) * (h - 2 * tf) ** 3) / 12
    props = beamfea.section_properties("i", h=h, b=b, tw=tw, tf=tf)
    assert props["Iy"] == pytest.approx(Iy, rel=1e-12)
    doc = cantilever(L=3.0, load=(0, 0, -1e4, 0, 0, 0))
    doc["sections"] = [{"id": "s", "shape": "i", "h": h, "b": b, "tw": tw, "tf": tf}]
    r = beamfea.run(doc)
    w = r["analyses"]["lin"]["nodes"]["B"]["displacement"][2]
    assert w == pytest.approx(-1e4 * 3.0**3 / (3 * 2.1e11 * Iy), rel=1e-9)


def test_bad_dimensions_raise_input_errors_naming_the_dimension():
    with pytest.raises(beamfea.InputError, match="tf: 2 tf must be below h"):
        beamfea.section_properties("i", h=0.1, b=0.1, tw=0.01, tf=0.06)
    with pytest.raises(beamfea.InputError, match="not 't'"):
        beamfea.section_properties("i", h=0.3, b=0.15, tw=0.0071, tf=0.0107, t=0.01)
    doc = cantilever()
    doc["sections"] = [{"id": "s", "shape": "box", "h": 0.1, "b": 0.1, "tw": 0.01}]
    with pytest.raises(beamfea.InputError) as e:
        beamfea.check(doc)
    assert e.value.pointer in ("/sections/0/t", "/sections/0/tw")


def test_the_sections_verb_computes_one_shape_and_refuses_bad_dimensions_with_exit_2():
    ok = subprocess.run([EXE, "sections", "--json", "box", "h=0.2", "b=0.1", "t=0.008"], capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr

    props = json.loads(ok.stdout)
    assert props["A"] == pytest.approx(0.2 * 0.1 - 0.184 * 0.084, rel=1e-12)
    bad = subprocess.run([EXE, "sections", "box", "h=0.2", "b=0.1", "t=0.06"], capture_output=True, text=True)
    assert bad.returncode == 2 and "t: 2 t must be below b and h" in bad.stderr
    unknown = subprocess.run([EXE, "sections", "hexagon"], capture_output=True, text=True)
    assert unknown.returncode == 2 and "unknown shape 'hexagon'" in unknown.stderr
