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


def test_targets_from_an_frf_document_are_the_command_lines(cli, tmp_path):
    # A hammer test of a 180 Hz oscillator, fitted by `frf --json`: its
    # peak is the target, and the blade's height falls with f ∝ h.
    from test_frf import F_N, hammer_hit, write_csv

    t, f, v = hammer_hit(seed=3)
    record = tmp_path / "hit.csv"
    write_csv(record, t, f, v)
    p = cli.run("frf", str(record), "--json")
    assert p.returncode == 0, p.stderr
    frf = tmp_path / "frf.json"
    frf.write_text(p.stdout)
    peaks = sorted(q["frequency_hz"] for q in json.loads(p.stdout)["peaks"])
    assert len(peaks) == 1 and abs(peaks[0] - F_N) < 1e-3 * F_N
    model = ancf_modal.Model.builtin("cantilever")
    # 180 Hz needs about a sixth of the blade's 1.1 mm: bounds below the
    # default's quarter.
    mine = model.calibrate(target_from=frf, params={"height": (1e-4, 2e-3)})
    theirs = cli.json(
        "calibrate", "models/cantilever.json", "--target-from", str(frf), "--param", "height=1e-4:2e-3"
    )
    assert mine.to_dict()["targets_hz"] == theirs["targets_hz"] == peaks
    assert mine.achieved_hz == pytest.approx(peaks, rel=1e-9)
    h0 = model.with_params({"height": 1.1e-3})
    assert mine.parameters["blade.height"] == pytest.approx(
        1.1e-3 * peaks[0] / first_bending(h0), rel=1e-3
    )
    # Refusals: the command line's message, the keyword named.
    frf.write_text('{"model": 1}')
    with pytest.raises(ancf_modal.ModelError) as e:
        model.calibrate(target_from=frf)
    assert str(e.value) == cli.error("calibrate", "models/cantilever.json", "--target-from", str(frf))
    assert "no `peaks` array" in str(e.value)
    with pytest.raises(ancf_modal.ModelError, match=r"^target_from `.*frf.json`: takes the targets from a file"):
        model.calibrate(target_hz=200.0, target_from=frf)
