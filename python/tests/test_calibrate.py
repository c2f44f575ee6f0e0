"""Model.calibrate: the fitted model reaches the target, the fit follows
beam theory, and the result is the command line's."""

import json

import numpy as np
import pytest

import ancf_modal


def first_bending(model):
    r = model.modal(modes=8)
    return r.frequencies_hz[[k == "bending" for k in r.kinds]][0]


def test_height_fit_reaches_the_target_and_follows_f_proportional_to_h():
    # A bare beam: f ∝ h, so the fitted height is h₀·target/f₀.
    model = ancf_modal.Model.builtin("beam_free_free")
    h0 = json.loads(model.to_json())["beams"][0]["section"]["height"]
    f0 = first_bending(model)
    target = 1.07 * f0
    result = model.calibrate(target_hz=target, params="height")
    (name, h) = next(iter(result.parameters.items()))
    assert name.endswith("height")  # the canonical name, `BEAM.height`
    assert h / h0 == pytest.approx(1.07, rel=1e-9)
    fitted = result.fitted_model
    assert first_bending(fitted) == pytest.approx(target, rel=1e-9)
    assert result.achieved_hz[0] == pytest.approx(target, rel=1e-9)
    assert result.initial_hz[0] == pytest.approx(f0, rel=1e-12)


def test_calibration_equals_the_command_line(cli):
    model = ancf_modal.Model.builtin()
    result = model.calibrate(target_hz=4600.0)
    doc = cli.json("calibrate", "--target", "4600")
    mine = result.to_dict()
    assert [p["fitted"] for p in mine["parameters"]] == pytest.approx(
        [p["fitted"] for p in doc["parameters"]], rel=1e-12
    )
    assert mine["evaluations"] == doc["evaluations"]
    assert repr(result).splitlines()[0] == cli.run("calibrate", "--target", "4600").stdout.splitlines()[0]


def test_unknown_calibration_parameter(cli):
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.Model.builtin().calibrate(params=["nonsense"])
    # The command line names the flag, the package the keyword argument.
    assert str(e.value) == cli.error("calibrate", "--param", "nonsense").replace(
        "--param: ", "params: ", 1
    )


def test_unreachable_target_is_a_model_error():
    with pytest.raises(ancf_modal.ModelError):
        ancf_modal.Model.builtin().calibrate(target_hz=1e9, params={"height": (1e-3, 1.2e-3)})
