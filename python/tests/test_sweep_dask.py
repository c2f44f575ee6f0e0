"""ancf_modal.sweep(..., client=...) on a Dask LocalCluster (two worker
processes) gives the local sweep's result to the last bit, in grid order:
the result does not depend on where its points are computed. Model and
SweepResult survive a pickle round trip unchanged."""

import hashlib
import json
import math
import os
import pickle
import signal
import threading
import time
import warnings

import numpy as np
import pytest

import ancf_modal

distributed = pytest.importorskip(
    "distributed",
    reason="dask.distributed is not installed (pip install './python[dask]' "
    "or -r python/tests/requirements.txt)",
)

# The paper's blade (Table 2) [m, m, m, Pa, kg/m³].
L, H, W, E, RHO = 25e-3, 1.1e-3, 5.2e-3, 127e9, 8940.0
MASS = 1e-3  # the oscillator's point mass [kg]


@pytest.fixture(scope="module")
def client():
    # One cluster for the module: two worker processes of one thread each,
    # no dashboard (other runs may hold its port).
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as c:
        yield c


def both(model, params, quantity, client, **kw):
    """The local sweep and the sweep on `client`, with the warnings each raised."""
    with warnings.catch_warnings(record=True) as local_w:
        warnings.simplefilter("always")
        local = ancf_modal.sweep(model, params, quantity, **kw)
    with warnings.catch_warnings(record=True) as remote_w:
        warnings.simplefilter("always")
        remote = ancf_modal.sweep(model, params, quantity, client=client, **kw)
    assert [str(w.message) for w in remote_w] == [str(w.message) for w in local_w]
    return local, remote


def assert_identical(local, remote):
    """The same result to the last bit, in the same order."""
    assert remote.to_dict() == local.to_dict()
    assert remote.values.tobytes() == local.values.tobytes()
    assert remote.result.tobytes() == local.result.tobytes()  # NaN where failed, too
    assert remote.errors == local.errors
    if local.frequencies_hz is not None:
        assert remote.frequencies_hz.tobytes() == local.frequencies_hz.tobytes()
    assert repr(remote) == repr(local)


def test_two_parameter_first_bending(client):
    # h/L = 0.128 > 0.1 at the largest height warns at points 3, 7 and 11,
    # which are in shards 4, 8 and 4 of 8: the warnings come in index order
    # all the same, as locally.
    model = ancf_modal.Model.builtin("beam_free_free")
    params = {"blade.young": [100e9, 127e9, 150e9], "height": (0.8e-3, 3.2e-3, 4)}
    local, remote = both(model, params, "first_bending_hz", client)
    assert_identical(local, remote)
    # Row-major, the first parameter slowest; f₁ ∝ h √E for the bare beam.
    e, h = remote.values[:, 0], remote.values[:, 1]
    assert np.array_equal(e, np.repeat([100e9, 127e9, 150e9], 4))
    assert np.allclose(h, np.tile(np.linspace(0.8e-3, 3.2e-3, 4), 3), rtol=1e-14, atol=0)
    ratio = remote.result / (h * np.sqrt(e))
    assert remote.failed_points == 0 and np.max(np.abs(ratio / ratio[0] - 1)) < 1e-9
    warned = [int(w.split("point ")[1].split(":")[0]) for w in remote.to_dict()["warnings"]]
    assert warned == [i for i in range(12) if h[i] / L > 0.1] == [3, 7, 11]


def cantilever_and_oscillator():
    """The blade clamped at s = 0 and, uncoupled beside it, a 1 g mass on a
    spring k: √(k/m)/2π crosses the cantilever's bending frequencies."""
    return ancf_modal.Model.from_json(json.dumps({
        "name": "crossing",
        "beams": [{"id": "blade", "start": [0.0, 0.0], "angle_deg": 0.0, "length": L,
                   "elements": 8, "section": {"height": H, "width": W},
                   "material": {"young": E, "density": RHO}}],
        "point_masses": [{"id": "m", "mass": MASS, "position": [0.1, 0.1]}],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [0.0, 0.0]},
             "b": {"beam": "blade", "s": 0.0}},
            {"id": "guide", "type": "slider", "a": {"ground": [0.1, 0.1]}, "b": {"body": "m"},
             "axis": [1.0, 0.0]},
        ],
        "springs": [{"id": "k", "a": {"ground": [0.09, 0.1]}, "b": {"body": "m"},
                     "stiffness": 1e4, "free_length": 0.01}],
    }))


def test_tracked_frequency_through_a_crossing(client):
    # 8 points over 2 workers: 8 shards of one point each, so the modes can
    # only be tracked after the gathering.
    model = cantilever_and_oscillator()
    params = {"springs[k].stiffness": (1e4, 4e6, 8, "log")}
    local, remote = both(model, params, "frequency:2", client, modes=3)
    assert_identical(local, remote)
    # Mode 2 at k = 1e4 N/m is the cantilever's first (the oscillator, at
    # 503 Hz, is mode 1); the spring does not touch it, so tracked it stays
    # Euler–Bernoulli's 1.8751²/(2πL²)·√(EI/ρA), while the sorted second
    # frequency becomes the cantilever's second as the oscillator passes.
    euler = 1.875104069**2 / (2 * math.pi * L**2) * math.sqrt(E * H**2 / (12 * RHO))
    f = remote.result
    assert np.max(np.abs(f / f[0] - 1)) < 1e-9 and abs(f[0] / euler - 1) < 1e-3
    k = remote.values[:, 0]
    oscillator = np.sqrt(k / MASS) / (2 * math.pi)
    assert np.max(np.abs(remote.frequencies_hz[:, 0] / oscillator - 1)) < 1e-9
    assert oscillator[-1] > np.sort(remote.frequencies_hz[-1])[1] > 5 * f[-1]


def test_switch_off_time_to_distance(client):
    model = ancf_modal.Model.builtin("rcbo_switch_off")
    params = {"load_scale:F_x2,helical_spring": (1.0, 2.0, 3)}
    local, remote = both(model, params, "time_to_distance_s", client, end_time=2.2e-3, step=2e-6)
    assert_identical(local, remote)
    t = remote.result
    # The paper's Fig. 10: a larger pre-stress opens the contact faster.
    assert remote.failed_points == 0 and t[0] > t[1] > t[2]
    # One parameter: every point's trace comes back (node 0's x over time).
    assert all(len(p["node0"]["x_m"]) > 10 for p in remote.to_dict()["points"])


def pinned_roller(p):
    """The blade pinned at s = 0, on a roller along x at s = L, which
    carries the axial force `p` [N] (negative: compression)."""
    return ancf_modal.Model.from_json(json.dumps({
        "name": "pinned_roller",
        "beams": [{"id": "b", "start": [0.0, 0.0], "angle_deg": 0.0, "length": L,
                   "elements": 8, "section": {"height": H, "width": W},
                   "material": {"young": E, "density": RHO}}],
        "joints": [
            {"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}},
            {"type": "slider", "a": {"ground": [L, 0.0]}, "b": {"beam": "b", "s": L},
             "axis": [1.0, 0.0]},
        ],
        "loads": [{"id": "P", "at": {"beam": "b", "s": L}, "force": [p, 0.0]}],
    }))


def test_a_design_past_buckling_fails_as_it_does_locally(client):
    # Euler's load π²EI/L²; the designs at 1.1 and 1.5 times it buckle.
    p_cr = math.pi**2 * E * W * H**3 / 12 / L**2
    scales = [0.0, 0.5, 1.1, 0.9, 1.5]
    local, remote = both(pinned_roller(-p_cr), {"load_scale:P": scales}, "frequency:1", client)
    assert_identical(local, remote)
    assert remote.failed_points == 2
    for s, f, e in zip(scales, remote.result, remote.errors):
        if s > 1:
            assert np.isnan(f) and "loses stability at load factor" in e
            # The reported critical factor × the design's scale is Euler's load.
            critical = float(e.split("load factor ")[1].split(" ")[0]) * s
            assert abs(critical - 1) < 5e-3
        else:
            # The others are kept: ω² = ω₀²(1 − P/P_cr) for the sine mode.
            assert e is None and abs(f / remote.result[0] - math.sqrt(1 - s)) < 0.02


@pytest.mark.filterwarnings("ignore::ancf_modal.ModelWarning")
def test_model_pickles_unchanged():
    for model in (
        ancf_modal.Model.builtin(),
        ancf_modal.Model.builtin("rcbo_switch_off"),
        pinned_roller(-100.0).with_params({"beams[b].section.height": 1.2e-3}),
    ):
        back = pickle.loads(pickle.dumps(model))
        assert type(back) is ancf_modal.Model
        assert back.to_json() == model.to_json()
        assert (back.name, back.source, back.sha256) == (model.name, model.source, model.sha256)
        assert repr(back) == repr(model)
        a, b = model.modal(modes=8), back.modal(modes=8)
        assert b.frequencies_hz.tobytes() == a.frequencies_hz.tobytes()
        assert b.to_dict() == a.to_dict()


def test_model_from_a_file_pickles_with_its_path_and_hash(tmp_path):
    # The file's own text (spaced as written) hashes differently from
    # to_json(); the pickle keeps the file's hash and path.
    path = tmp_path / "roller.json"
    path.write_text(pinned_roller(-100.0).to_json().replace("\n", "\n  "))
    model = ancf_modal.Model.from_json(path)
    assert model.sha256 != hashlib.sha256(model.to_json().encode()).hexdigest()
    back = pickle.loads(pickle.dumps(model))
    assert (back.source, back.sha256) == (str(path), model.sha256)
    assert back.to_json() == model.to_json()


def test_sweep_result_pickles_unchanged():
    params = {"springs[k].stiffness": (1e4, 4e6, 4, "log")}
    model = cantilever_and_oscillator()
    for r in (
        ancf_modal.sweep(model, params, "frequency:2", modes=3),
        ancf_modal.sweep(model, params, "frequency:2", modes=3, shard=(2, 3)),
    ):
        back = pickle.loads(pickle.dumps(r))
        assert type(back) is ancf_modal.SweepResult
        assert_identical(r, back)
    # A shard read back still merges (its mode shapes kept exactly).
    shards = [ancf_modal.sweep(model, params, "frequency:2", modes=3, shard=(k, 2)) for k in (1, 2)]
    merged = ancf_modal.sweep_merge([pickle.loads(pickle.dumps(s)) for s in shards])
    whole = ancf_modal.sweep(model, params, "frequency:2", modes=3)
    assert merged.to_dict()["points"] == whole.to_dict()["points"]


def test_client_arguments(client):
    model = ancf_modal.Model.builtin("beam_free_free")
    params = {"height": (0.8e-3, 1.4e-3, 2)}
    with pytest.raises(ancf_modal.ModelError, match=r"^threads `2`: with a client"):
        ancf_modal.sweep(model, params, "first_bending_hz", client=client, threads=2)
    with pytest.raises(ancf_modal.ModelError, match=r"^shard `\(1, 2\)`: with a client"):
        ancf_modal.sweep(model, params, "first_bending_hz", client=client, shard=(1, 2))
    with pytest.raises(ancf_modal.ModelError, match=r"^client `'tcp://x:1'`: must be a dask"):
        ancf_modal.sweep(model, params, "first_bending_hz", client="tcp://x:1")
    with pytest.raises(ancf_modal.ModelError, match=r"^progress `True`: .* needs a client"):
        ancf_modal.sweep(model, params, "first_bending_hz", progress=True)
    # A bad request is refused before anything is sent, as locally.
    for bad in ({"quantity": "nope"}, {"modes": 0}):
        kw = {"quantity": "first_bending_hz", **bad}
        with pytest.raises(ancf_modal.ModelError) as here:
            ancf_modal.sweep(model, params, **kw)
        with pytest.raises(ancf_modal.ModelError) as there:
            ancf_modal.sweep(model, params, client=client, **kw)
        assert str(there.value) == str(here.value)


def test_a_closed_client_or_one_without_workers_is_named():
    # The trial's case: Dask's own AttributeError came out of a closed client.
    model = ancf_modal.Model.builtin("beam_free_free")
    params = {"height": (0.8e-3, 1.4e-3, 2)}
    with distributed.LocalCluster(
        n_workers=0, processes=False, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as empty:
        with pytest.raises(ancf_modal.ModelError, match=r"no workers yet"):
            ancf_modal.sweep(model, params, "first_bending_hz", client=empty)
        empty.close()
        with pytest.raises(ancf_modal.ModelError, match=r"not running"):
            ancf_modal.sweep(model, params, "first_bending_hz", client=empty)


def test_keyboard_interrupt_cancels_the_tasks(client):
    # Ctrl-C (SIGINT) half a second into 40 switch-off points (~3 s of work
    # on two workers): the call stops within a second, and the cluster
    # holds none of its tasks or data afterwards.
    model = ancf_modal.Model.builtin("rcbo_switch_off")
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        ancf_modal.sweep(
            model, {"load_scale:F_x2,helical_spring": (1.0, 2.0, 40)}, "time_to_distance_s",
            client=client,
        )
    stopped = time.perf_counter() - start
    timer.cancel()
    assert stopped < 0.5 + 1.0, stopped
    # The client wants nothing of it any more; the scheduler lets go of the
    # scattered model and the shards soon after.
    assert not client.futures
    deadline = time.perf_counter() + 2.0
    while client.who_has() and time.perf_counter() < deadline:
        time.sleep(0.05)
    assert not client.who_has() and all(not t for t in client.processing().values())
