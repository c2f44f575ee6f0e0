"""Model.transient: a cantilever under a suddenly applied tip load."""

import json

import numpy as np
import pytest

import ancf_modal
from conftest import close_documents

ARGS = dict(end_time=0.02, step=2e-6, sample_rate=0.0, spectral_radius=1.0)


@pytest.fixture(scope="module")
def cantilever():
    model = ancf_modal.Model.builtin("cantilever")
    return model, model.transient(**ARGS)


def static_tip(model):
    doc = json.loads(model.to_json())
    (beam,) = doc["beams"]
    (load,) = doc["loads"]
    section, material = beam["section"], beam["material"]
    ei = material["young"] * section["width"] * section["height"] ** 3 / 12.0
    return load["force"][1] * beam["length"] ** 3 / (3 * ei)


def test_step_load_response_oscillates_about_the_static_deflection(cantilever):
    model, r = cantilever
    tip = r.sensors["tip"]
    assert tip.shape == r.time.shape
    delta = static_tip(model)
    # A load applied at once from rest: the response swings between 0 and
    # twice the static deflection (undamped, ρ∞ = 1), about its mean.
    assert np.max(tip) / delta == pytest.approx(2.0, rel=2e-2)
    f1 = ancf_modal.Model.builtin("cantilever").modal(modes=4).frequencies_hz[0]
    periods = int(r.time[-1] * f1)
    whole = r.time <= periods / f1  # whole periods of the first mode
    assert np.mean(tip[whole]) / delta == pytest.approx(1.0, rel=2e-2)
    energy = r.to_dict()["energy"]
    assert abs(energy["error_j"]) < 1e-6 * abs(energy["load_work_j"])


def test_equals_the_command_line(cli, cantilever):
    _, r = cantilever
    doc = cli.json(
        "transient", "models/cantilever.json", "--end-time", "0.02", "--step", "2e-6",
        "--sample-rate", "0", "--spectral-radius", "1",
    )
    close_documents(r.to_dict(), doc, rtol=1e-9)


def test_bad_spectral_radius(cli):
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.Model.builtin("cantilever").transient(spectral_radius=1.5)
    line = cli.error("transient", "models/cantilever.json", "--spectral-radius", "1.5")
    assert str(e.value) == line.replace("--spectral-radius", "spectral_radius", 1)
