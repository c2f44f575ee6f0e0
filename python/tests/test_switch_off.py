"""Model.switch_off against its own samples, the energy balance and the
command line."""

import json

import numpy as np
import pytest

import ancf_modal


@pytest.fixture(scope="module")
def run():
    return ancf_modal.Model.builtin("rcbo_switch_off").switch_off(no_step_check=True)


def test_the_tracked_point_travels_the_distance_at_the_reported_time(run):
    t, x = run.time, run.x
    travel = x - x[0]  # along the default direction (1, 0)
    td = run.time_to_distance_s
    assert td is not None and 0 < td < t[-1]
    k = np.searchsorted(t, td)
    # The samples bracketing the reported time bracket the distance.
    assert travel[k - 1] < 2e-3 <= travel[k] + 1e-12
    # The released load (a step at t = 0) is gone after the start.
    for label, f in run.released_loads.items():
        assert f.shape == t.shape and np.all(f[1:] == 0.0), label


def test_energy_balance(run):
    energy = run.to_dict()["energy"]
    # README: the balance error is 3.3e-4 of the stored energy (the pin's
    # impacts each add theirs), under the 1e-3 a warning starts at.
    assert abs(energy["error_j"]) < 1e-3 * energy["stored_j"]


def test_one_number_is_calibrated_and_the_uncalibrated_time_is_beside_it(run):
    doc = run.to_dict()
    model = json.loads(ancf_modal.Model.builtin("rcbo_switch_off").to_json())
    assert doc["calibrated"] == model["calibrated"]
    assert [c["name"] for c in doc["calibrated"]] == ["loads[0].at.s"]
    assert doc["calibrated"][0]["value"] == model["loads"][0]["at"]["s"]
    assert run.time_to_distance_s == pytest.approx(1.75e-3, rel=1e-4)
    tip = ancf_modal.Model.builtin("rcbo_switch_off_uncalibrated").switch_off(no_step_check=True)
    assert doc["uncalibrated"]["time_to_distance_s"] == tip.time_to_distance_s


def test_equals_the_command_line(cli, run):
    doc = cli.json("switch-off", "models/rcbo_switch_off.json", "--no-step-check")
    assert run.time_to_distance_s == pytest.approx(doc["time_to_distance_s"], rel=1e-12)
    mine = run.to_dict()
    assert np.allclose(mine["node0"]["x_m"], doc["node0"]["x_m"], rtol=0, atol=1e-15)
    assert cli.run("switch-off", "models/rcbo_switch_off.json", "--no-step-check").stdout.startswith(
        repr(run).splitlines()[0]
    )


def test_bad_point_names_the_argument(cli):
    model = ancf_modal.Model.builtin("rcbo_switch_off")
    with pytest.raises(ancf_modal.ModelError) as e:
        model.switch_off(point="nobody", end_time=1e-5, no_step_check=True)
    line = cli.error(
        "switch-off", "models/rcbo_switch_off.json", "--point", "nobody", "--end-time", "1e-5",
        "--no-step-check",
    )
    assert str(e.value) == line.replace("--point: ", "point: ", 1)


def test_fig10_equals_the_command_line(cli):
    """The paper's Fig. 10 study (`switch-off --fig10`): the same rows from
    Python as from the command line, and the combined ratio the combined
    time over the reference's (a prediction of the model whose F_x² point
    is calibrated)."""
    run = ancf_modal.Model.builtin("rcbo_switch_off").switch_off(no_step_check=True, fig10=True)
    doc = cli.json("switch-off", "models/rcbo_switch_off.json", "--no-step-check", "--fig10")
    study = run.fig10
    assert study == run.to_dict()["fig10"]
    assert [r["change"] for r in study["rows"]] == [r["change"] for r in doc["fig10"]["rows"]]
    for mine, theirs in zip(study["rows"], doc["fig10"]["rows"]):
        assert mine["time_to_distance_s"] == pytest.approx(theirs["time_to_distance_s"], rel=1e-12)
    rows = study["rows"]
    assert rows[0]["time_to_distance_s"] == run.time_to_distance_s
    assert study["combined_ratio"] == pytest.approx(
        rows[-1]["time_to_distance_s"] / rows[0]["time_to_distance_s"], rel=1e-12
    )
    assert study["paper_combined_ratio"] == pytest.approx(1 / 3)
    assert study["calibrated"] == run.to_dict()["calibrated"] != []
    # Without the flag there is no study.
    assert ancf_modal.Model.builtin("rcbo_switch_off").switch_off(
        no_step_check=True, end_time=1e-4
    ).fig10 is None
