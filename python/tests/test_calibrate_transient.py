"""Model.calibrate(quantity="time_to_distance_s", ...) and
Model.calibrate(trajectory=...): the same request as the command line's
`calibrate --quantity` / `--trajectory`, so the same fit; a trajectory
simulated at known parameter values is fitted back to them."""

import json

import numpy as np
import pytest

import ancf_modal

HOUSING_Y = "springs[helical_spring].a.ground[1]"
PRELOAD = "springs[helical_spring].preload"


@pytest.fixture(scope="module")
def model():
    return ancf_modal.Model.builtin("rcbo_switch_off")


def spring(model):
    return json.loads(model.to_json())["springs"][0]


def test_time_fit_equals_the_command_line(cli, model):
    y0 = spring(model)["a"]["ground"][1]
    bounds = (y0 - 1e-3, y0 + 1e-3)
    result = model.calibrate(
        quantity="time_to_distance_s", target=1.8e-3, params={HOUSING_Y: bounds}
    )
    assert isinstance(result, ancf_modal.TransientCalibrationResult)
    doc = cli.json(
        "calibrate", "models/rcbo_switch_off.json", "--quantity", "time_to_distance_s",
        "--target", "1.8e-3", "--param", f"{HOUSING_Y}={bounds[0]!r}:{bounds[1]!r}",
    )
    mine = result.to_dict()
    assert mine["calibrated"] == doc["calibrated"]
    assert [p["fitted"] for p in mine["parameters"]] == [p["fitted"] for p in doc["parameters"]]
    # The fit reaches the target within its default tolerance (1e-5 × target)
    # and says what it fitted.
    assert result.achieved_time_s == pytest.approx(1.8e-3, rel=1e-5)
    assert result.standard_errors == {mine["calibrated"][0]["name"]: None}
    assert "time_to_distance_s" in mine["calibrated"][0]["target"]


def test_trajectory_fit_recovers_the_design_and_equals_the_command_line(cli, tmp_path):
    # The switch-off of a design with the housing 1 mm higher and the
    # preload ×1.1, at its own (adaptive) step and the camera's rate, to
    # 0.6 ms: fitted from the unmoved model, both come back. On the
    # uncalibrated companion, whose pin stays on its end cap (in the
    # calibrated model the pin strikes its slot, and the path follows the
    # impacts).
    model = ancf_modal.Model.builtin("rcbo_switch_off_uncalibrated")
    s = spring(model)
    y_true, p_true = s["a"]["ground"][1] + 1e-3, 1.1 * s["preload"]
    moved = json.loads(model.to_json())
    moved["springs"][0]["a"]["ground"][1] = y_true
    moved["springs"][0]["preload"] = p_true
    run = ancf_modal.Model.from_json(json.dumps(moved)).switch_off(no_step_check=True)
    keep = run.time <= 0.6e-3
    t, x, y = run.time[keep], run.x[keep], run.y[keep]
    params = {HOUSING_Y: (y_true - 2e-3, y_true + 1e-3), PRELOAD: (2 * p_true, 0.5 * p_true)}
    result = model.calibrate(trajectory=(t, x, y), params=params)
    fitted = list(result.parameters.values())
    assert fitted[0] == pytest.approx(y_true, rel=1e-6)
    assert fitted[1] == pytest.approx(p_true, rel=1e-6)
    assert all(se is not None and se >= 0 for se in result.standard_errors.values())
    # The same samples as a CSV file, through the command line.
    csv = tmp_path / "trajectory.csv"
    np.savetxt(csv, np.column_stack([t, x, y]), delimiter=",", fmt="%.17e", header="t,x,y")
    args = ["calibrate", "models/rcbo_switch_off_uncalibrated.json", "--trajectory", str(csv)]
    for name, (lo, hi) in params.items():
        args += ["--param", f"{name}={lo!r}:{hi!r}"]
    doc = cli.json(*args)
    assert [p["fitted"] for p in doc["parameters"]] == fitted
    assert [c["standard_error"] for c in doc["calibrated"]] == list(result.standard_errors.values())


def test_transient_keywords_are_checked(model):
    with pytest.raises(ancf_modal.ModelError, match="target_hz"):
        model.calibrate(quantity="time_to_distance_s", target_hz=4600.0, params=HOUSING_Y)
    with pytest.raises(ancf_modal.ModelError, match="^target "):
        model.calibrate(target=1e-3)
    with pytest.raises(ancf_modal.ModelError, match="trajectory"):
        model.calibrate(trajectory=([0.0, 1e-4], [0.0], [0.0, 0.0]), params=HOUSING_Y)
