"""ancf_modal.sweep: beam theory over a grid, the command line's document,
failed points, and KeyboardInterrupt."""

import _thread
import json
import threading
import time

import numpy as np
import pytest

import ancf_modal


def test_first_bending_is_proportional_to_the_height():
    model = ancf_modal.Model.builtin("beam_free_free")
    r = ancf_modal.sweep(model, {"height": (0.5e-3, 2e-3, 7)}, "first_bending_hz")
    h = r.values[:, 0]
    assert r.names == ["height"] and r.failed_points == 0
    assert np.allclose(h, np.linspace(0.5e-3, 2e-3, 7), rtol=1e-14)
    ratio = r.result / h
    # f ∝ h (EI/ρA = E h²/12ρ) for the bare beam.
    assert np.max(np.abs(ratio / ratio[0] - 1.0)) < 1e-9


def test_listed_values_follow_the_command_line(cli):
    # A list (or array) of values is swept as listed, as `--param height=V1,V2,…`;
    # f ∝ h across them.
    model = ancf_modal.Model.builtin("beam_free_free")
    listed = ancf_modal.sweep(model, {"height": [1.2e-3, 0.6e-3]}, "first_bending_hz")
    as_array = ancf_modal.sweep(model, {"height": np.array([1.2e-3, 0.6e-3])}, "first_bending_hz")
    assert listed.to_dict() == as_array.to_dict()
    assert list(listed.values[:, 0]) == [1.2e-3, 0.6e-3]
    assert abs(listed.result[0] / listed.result[1] / 2.0 - 1.0) < 1e-9
    doc = cli.json(
        "sweep", "models/beam_free_free.json", "--param", "height=1.2e-3,6e-4",
        "--quantity", "first_bending_hz",
    )
    assert [p["result"] for p in doc["points"]] == list(listed.result)


def test_grid_order_threads_and_the_command_line(cli):
    model = ancf_modal.Model.builtin()
    params = {"blade.young": "100e9:150e9:3", "height": (0.9e-3, 1.3e-3, 4)}
    parallel = ancf_modal.sweep(model, params, "frequency:1")
    serial = ancf_modal.sweep(model, params, "frequency:1", threads=1)
    assert parallel.to_dict() == serial.to_dict()
    assert parallel.values.shape == (12, 2)
    # Row-major: the first parameter varies slowest.
    assert np.all(parallel.values[:4, 0] == 100e9) and len(set(parallel.values[:4, 1])) == 4
    assert parallel.frequencies_hz.shape == (12, 6)
    # frequency:1 is the first tracked mode.
    assert np.array_equal(parallel.result, parallel.frequencies_hz[:, 0])
    doc = cli.json(
        "sweep",
        "--param",
        "blade.young=100e9:150e9:3",
        "--param",
        "height=9e-4:1.3e-3:4",
        "--quantity",
        "frequency:1",
    )
    mine = parallel.to_dict()
    for key in ("model", "quantity", "total_points", "prestress", "tracked_modes", "failed_points"):
        assert mine[key] == doc[key], key
    assert np.allclose(
        [p["result"] for p in mine["points"]], [p["result"] for p in doc["points"]], rtol=1e-12
    )
    assert repr(parallel).splitlines()[0] == cli.run(
        "sweep", "--param", "blade.young=100e9:150e9:3", "--param", "height=9e-4:1.3e-3:4",
        "--quantity", "frequency:1",
    ).stdout.splitlines()[0]


def test_a_failed_point_is_recorded():
    model = ancf_modal.Model.builtin("beam_free_free")
    r = ancf_modal.sweep(model, {"height": (-1e-3, 1e-3, 3)}, "first_bending_hz")
    assert r.failed_points == 2  # −1 mm and 0 mm
    assert np.isnan(r.result[0]) and np.isfinite(r.result[2])
    assert "must be positive" in r.errors[0] and r.errors[2] is None


def test_bad_quantity_and_parameter(cli):
    model = ancf_modal.Model.builtin()
    with pytest.raises(ancf_modal.ModelError, match=r"^quantity `nonsense`: "):
        ancf_modal.sweep(model, {"height": (1e-3, 1.2e-3, 2)}, "nonsense")
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.sweep(model, {"nope": (1, 2, 2)}, "first_bending_hz")
    line = cli.error("sweep", "--param", "nope=1:2:2", "--quantity", "first_bending_hz")
    assert str(e.value) == line.replace("--param: ", "params: ", 1)


def test_keyboard_interrupt_stops_a_sweep_within_a_second():
    # 20,000 points of a 100-element cantilever: minutes of work.
    model = ancf_modal.Model.builtin("cantilever").with_params({"beams[0].elements": 100})
    timer = threading.Timer(0.5, _thread.interrupt_main)
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        ancf_modal.sweep(model, {"height": (0.5e-3, 2e-3, 20000)}, "first_bending_hz")
    stopped = time.perf_counter() - start
    timer.cancel()
    assert stopped < 0.5 + 1.0, stopped


def test_shard_is_a_pair_as_a_tuple_or_a_list():
    # The outside-eyes trial: `shard=[1, 2]` was a TypeError.
    model = ancf_modal.Model.builtin("beam_free_free")
    params = {"height": [1e-3, 2e-3, 3e-3]}
    as_tuple = ancf_modal.sweep(model, params, "first_bending_hz", threads=1, shard=(1, 2))
    as_list = ancf_modal.sweep(model, params, "first_bending_hz", threads=1, shard=[1, 2])
    assert as_list.to_dict() == as_tuple.to_dict()
    with pytest.raises(ancf_modal.ModelError, match=r"shard `\[1, 2, 3\]`: must be a pair"):
        ancf_modal.sweep(model, params, "first_bending_hz", shard=[1, 2, 3])
