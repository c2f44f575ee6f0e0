"""Model.static and Model.impulse against beam theory, the eigenvalues and
the command line."""

import json

import numpy as np
import pytest

import ancf_modal
from conftest import close_documents


def test_cantilever_tip_deflection():
    model = ancf_modal.Model.builtin("cantilever")
    doc = json.loads(model.to_json())
    (beam,) = doc["beams"]
    (load,) = doc["loads"]
    length, section, material = beam["length"], beam["section"], beam["material"]
    ei = material["young"] * section["width"] * section["height"] ** 3 / 12.0
    p = load["force"][1]
    result = model.static()
    tip = max(result.to_dict()["nodes"], key=lambda n: n["s"])
    # P L³/(3 E I); at P L²/EI ≈ 1e-3 the elastica differs by ~1e-7.
    expected = p * length**3 / (3 * ei)
    assert abs(tip["displacement"][1] / expected - 1.0) < 1e-4
    assert result.residual <= 1e-8 * abs(p)
    half = model.static(load_scale=0.5).to_dict()
    tip_half = max(half["nodes"], key=lambda n: n["s"])
    assert abs(tip_half["displacement"][1] / expected - 0.5) < 1e-4


def test_static_document_and_table_equal_the_command_line(cli):
    model = ancf_modal.Model.builtin("rcbo_prestressed")
    result = model.static()
    close_documents(result.to_dict(), cli.json("static", "models/rcbo_prestressed.json"))
    assert repr(result) == cli.shown("static", "models/rcbo_prestressed.json")
    assert len(result.q) == len(model.coordinates())


def test_impulse_peak_against_the_eigenvalue(cli):
    model = ancf_modal.Model.builtin()
    args = dict(end_time=0.05, step=2.5e-5, sample_rate=0.0)
    result = model.impulse(**args)
    raw, corrected, eigen = result.first_bending
    f1 = model.modal().frequencies_hz[3]
    assert eigen == pytest.approx(f1, rel=1e-12)
    # The integrator shortens periods by ≈ (ωh)²/12; corrected, the FFT
    # peak is the eigenvalue's (README: within 4e-6 at h = 5e-5 s).
    wh = 2 * np.pi * f1 * args["step"]
    assert abs(raw / f1 - 1.0) < wh**2 / 12 * 2 + 1e-4
    assert abs(corrected / f1 - 1.0) < 1e-4
    assert len(result.time) == len(result.signal) == len(result.force)
    assert np.allclose(np.diff(result.time), args["step"], rtol=1e-9)
    assert result.force.max() == pytest.approx(4.0, rel=1e-2)  # the model's 4 N pulse
    doc = cli.json("impulse", "--end-time", "0.05", "--step", "2.5e-5", "--sample-rate", "0")
    close_documents(
        {k: v for k, v in result.to_dict().items() if k not in ("stats",)}, doc, rtol=1e-9
    )


def test_impulse_argument_errors(cli):
    model = ancf_modal.Model.builtin()
    with pytest.raises(ancf_modal.ModelError) as e:
        model.impulse(step=-1e-6)
    cli_line = cli.error("impulse", "--step", "-1e-6")
    assert str(e.value).startswith("step `")
    assert str(e.value).split("`: ", 1)[1] == cli_line.split("`: ", 1)[1]
    with pytest.raises(ancf_modal.ModelError) as e:
        model.impulse(sensor="nowhere", end_time=1e-3)
    assert str(e.value) == cli.error("impulse", "--sensor", "nowhere", "--end-time", "1e-3")
