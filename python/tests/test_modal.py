"""Model.modal against the command line, Euler–Bernoulli theory and the
returned matrices."""

import json
import math

import numpy as np
import pytest

import ancf_modal
from conftest import model_args

NAMES = ancf_modal.Model.builtin_names()


def relative(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    scale = np.maximum(np.abs(b), 1e-300)
    return np.max(np.abs(a - b) / scale) if a.size else 0.0


@pytest.mark.parametrize("name", NAMES)
def test_frequencies_equal_the_command_line(cli, name):
    result = ancf_modal.Model.builtin(name).modal()
    doc = cli.json("modal", *model_args(name))
    expected = [m["frequency_hz"] for m in doc["modes"]]
    assert len(result.frequencies_hz) == len(expected)
    assert relative(result.frequencies_hz, expected) <= 1e-12
    assert result.kinds == [m["kind"] for m in doc["modes"]]
    assert result.rigid_modes == doc["rigid_modes"]
    assert result.mechanism_modes == doc["mechanism_modes"]


def test_to_dict_agrees_with_the_command_line_json(cli):
    result = ancf_modal.Model.builtin().modal(modes=8)
    mine = result.to_dict()
    doc = cli.json("modal", "--modes", "8")
    # Every key the package gives is the command line's, with its value
    # (frequencies to round-off of a separate build).
    for key, value in mine.items():
        assert key in doc, key
        if key == "modes":
            continue
        assert value == doc[key], key
    assert len(mine["modes"]) == len(doc["modes"])
    for a, b in zip(mine["modes"], doc["modes"]):
        for key, value in a.items():
            if isinstance(value, float):
                assert relative(value, b[key]) <= 1e-12, key
            elif key != "energy":
                assert value == b[key], key
    assert mine["tool_version"] == ancf_modal.__version__


def test_prestressed_frequencies_equal_the_command_line(cli):
    model = ancf_modal.Model.builtin("rcbo_prestressed")
    result = model.modal(prestress=True, modes=8)
    doc = cli.json("modal", "models/rcbo_prestressed.json", "--prestress", "--modes", "8")
    expected = [m["frequency_hz"] for m in doc["modes"]]
    assert relative(result.frequencies_hz, expected) <= 1e-12
    # The pre-stress moves the frequencies (README: +0.06 % on the first
    # bending mode), so the two results are not the same computation.
    plain = model.modal(modes=8).frequencies_hz
    assert np.max(np.abs(result.frequencies_hz - plain)) > 0.0


def test_repr_is_the_command_line_table(cli):
    result = ancf_modal.Model.builtin().modal(modes=6)
    assert repr(result) == cli.shown("modal", "--modes", "6")
    row = repr(result).splitlines()[3 + 3]  # title, counts, header, modes 1–3
    assert row.split()[:2] == ["4", f"{result.frequencies_hz[3]:.3f}"]


def free_free_euler_bernoulli_hz(model_json):
    """First free-free bending frequency of the model's only beam, from
    Euler–Bernoulli theory: f = (βL)²/(2πL²)·√(EI/ρA), βL = 4.730040745."""
    (beam,) = model_json["beams"]
    length = beam["length"]
    h, w = beam["section"]["height"], beam["section"]["width"]
    e, rho = beam["material"]["young"], beam["material"]["density"]
    ei, rho_a = e * w * h**3 / 12.0, rho * w * h
    return 4.730040745**2 / (2 * math.pi * length**2) * math.sqrt(ei / rho_a)


def test_free_beam_against_euler_bernoulli():
    model = ancf_modal.Model.builtin("beam_free_free")
    result = model.modal(modes=6)
    f1 = result.frequencies_hz[[k == "bending" for k in result.kinds]][0]
    exact = free_free_euler_bernoulli_hz(json.loads(model.to_json()))
    # Hermite cubics converge from above; 8 elements: ~8e-5 (README).
    assert 0.0 < (f1 - exact) / exact < 1e-4


def test_with_params_scales_a_bending_frequency_with_the_height():
    model = ancf_modal.Model.builtin("beam_free_free")
    h0 = json.loads(model.to_json())["beams"][0]["section"]["height"]
    beam_id = json.loads(model.to_json())["beams"][0]["id"]

    def first_bending(m):
        r = m.modal(modes=6)
        return r.frequencies_hz[[k == "bending" for k in r.kinds]][0]

    f0 = first_bending(model)
    thicker = model.with_params({f"beams[{beam_id}].section.height": 1.3 * h0})
    # EI/ρA ∝ h²: f ∝ h (Euler–Bernoulli), also for the discretized cable
    # linearized at its straight reference.
    assert abs(first_bending(thicker) / f0 - 1.3) < 1e-9
    # The short name of `calibrate --param` names the same number.
    assert first_bending(model.with_params({"height": 1.3 * h0})) == first_bending(thicker)


def test_with_params_equals_editing_the_json():
    model = ancf_modal.Model.builtin()
    doc = json.loads(model.to_json())
    doc["beams"][0]["material"]["young"] = 1.1e11
    doc["rigid_bodies"][0]["mass"] *= 1.5
    edited = ancf_modal.Model.from_json(json.dumps(doc))
    changed = model.with_params(
        {
            f"beams[{doc['beams'][0]['id']}].material.young": 1.1e11,
            "rigid_bodies[0].mass": doc["rigid_bodies"][0]["mass"],
        }
    )
    assert json.loads(changed.to_json()) == json.loads(edited.to_json())
    assert np.array_equal(changed.modal().frequencies_hz, edited.modal().frequencies_hz)
    assert not np.array_equal(changed.modal().frequencies_hz, model.modal().frequencies_hz)


def dense(matrices):
    return {k: v.toarray() for k, v in matrices.items()}


@pytest.mark.parametrize("name", ["rcbo_free_free", "cantilever", "rcbo_switch_off"])
def test_shapes_against_the_matrices(name):
    model = ancf_modal.Model.builtin(name)
    result = model.modal(modes=10)
    mats = dense(model.matrices())
    m, k, cq = mats["M"], mats["K"], mats["C_q"]
    phi = result.shapes
    n = len(model.coordinates())
    assert phi.shape == (len(result.frequencies_hz), n)
    assert m.shape == k.shape == (n, n) and cq.shape[1] == n
    # M symmetric positive semidefinite.
    assert np.array_equal(m, m.T)
    assert np.min(np.linalg.eigvalsh(m)) >= -1e-12 * np.max(np.abs(m))
    # Mass-normalized, and within the constraints.
    for p in phi:
        assert abs(p @ m @ p - 1.0) <= 1e-10
        assert np.max(np.abs(cq @ p)) <= 1e-10 * np.max(np.abs(cq)) * np.linalg.norm(p)
    # K φ − ω² M φ is a constraint force C_qᵀμ: its least-squares remainder
    # is round-off, against the norm-wise scale (‖K‖ + |ω²|‖M‖)‖φ‖ of a
    # backward error (a rigid mode's K φ is itself round-off).
    norm_k, norm_m = np.linalg.norm(k, 2), np.linalg.norm(m, 2)
    for p, w2, kind in zip(phi, result.eigenvalues, result.kinds):
        r = k @ p - w2 * (m @ p)
        mu, *_ = np.linalg.lstsq(cq.T, r, rcond=None)
        remainder = np.linalg.norm(r - cq.T @ mu)
        scale = (norm_k + abs(w2) * norm_m) * np.linalg.norm(p)
        assert remainder <= 1e-10 * scale, (kind, remainder / scale)
    # Mass-orthogonal modes.
    gram = phi @ m @ phi.T
    assert np.max(np.abs(gram - np.eye(len(phi)))) <= 1e-9


def test_matrices_as_arrays_equal_scipy():
    model = ancf_modal.Model.builtin()
    sp = model.matrices(format="scipy")
    arrays = model.matrices(format="arrays")
    for key in ("M", "K", "C_q"):
        data, indices, indptr, shape = arrays[key]
        assert tuple(shape) == sp[key].shape
        assert np.array_equal(data, sp[key].data)
        assert np.array_equal(indices, sp[key].indices)
        assert np.array_equal(indptr, sp[key].indptr)


def test_prestressed_stiffness_is_symmetric_and_differs():
    model = ancf_modal.Model.builtin("rcbo_prestressed")
    k0 = model.matrices()["K"].toarray()
    k = model.matrices(prestress=True)["K"].toarray()
    scale = np.max(np.abs(k))
    assert np.max(np.abs(k - k.T)) <= 1e-12 * scale
    assert np.max(np.abs(k - k0)) > 1e-9 * scale


def test_coordinates_name_every_coordinate():
    model = ancf_modal.Model.builtin()
    labels = model.coordinates()
    doc = json.loads(model.to_json())
    bodies = len(doc.get("rigid_bodies", []))
    assert sum("rigid body" in l for l in labels) == 3 * bodies
    assert sum(l.endswith(" rx") for l in labels) == sum(l.endswith(" r'y") for l in labels)
    assert len(set(labels)) == len(labels)


def test_mac_of_a_result_with_itself_and_a_perturbed_model():
    model = ancf_modal.Model.builtin()
    a = model.modal(modes=8)
    mac = a.mac(a)
    elastic = sum(k not in ("rigid", "mechanism") for k in a.kinds)
    assert mac.shape == (elastic, elastic)
    assert np.allclose(np.diag(mac), 1.0, atol=1e-12)
    assert np.allclose(mac, mac.T, atol=1e-12)
    h = json.loads(model.to_json())["beams"][0]["section"]["height"]
    b = model.with_params({"height": 1.001 * h}).modal(modes=8)
    assert np.all(np.diag(a.mac(b)) > 0.99)


def test_write_uff_reads_back_with_pyuff(tmp_path):
    pyuff = pytest.importorskip("pyuff")
    result = ancf_modal.Model.builtin().modal(modes=8)
    path = tmp_path / "modes.uff"
    result.write_uff(path)
    sets = pyuff.UFF(str(path)).read_sets()
    sets = sets if isinstance(sets, list) else [sets]
    modes = [s for s in sets if s["type"] == 55]
    elastic = result.frequencies_hz[[k not in ("rigid", "mechanism") for k in result.kinds]]
    assert len(modes) == len(elastic)
    freqs = [s["freq"] for s in modes]
    # Dataset 55 writes the frequency with 6 significant digits.
    assert relative(freqs, elastic) <= 1e-5
    nodes = [s for s in sets if s["type"] == 15]
    assert nodes and all(len(m["node_nums"]) == len(nodes[0]["node_nums"]) for m in modes)


def test_plot_writes_an_svg(tmp_path):
    result = ancf_modal.Model.builtin().modal(modes=8)
    path = tmp_path / "modes.svg"
    result.plot(path)
    text = path.read_text()
    assert "<svg" in text and "Mode 4" in text


def test_a_reference_that_is_no_equilibrium_is_said_and_warned(cli):
    # The switch-off model's reference carries the spring's preload: not an
    # equilibrium (as the command line says); its negative eigenvalue is
    # never reported at 0 Hz, and the warning arrives as a Python warning.
    model = ancf_modal.Model.builtin("rcbo_switch_off")
    with pytest.warns(ancf_modal.ModelWarning, match="not an equilibrium"):
        result = model.modal(modes=6)
    doc = cli.json("modal", "models/rcbo_switch_off.json", "--modes", "6")
    assert result.equilibrium == doc["equilibrium"]
    assert result.equilibrium["balanced"] is False
    assert result.negative_modes == doc["negative_modes"] >= 1
    assert result.unstable_modes == 0
    negative = result.eigenvalues < 0
    assert np.all(result.frequencies_hz[negative] < 0)
    assert np.allclose(
        -result.frequencies_hz[negative],
        np.sqrt(-result.eigenvalues[negative]) / (2 * math.pi),
        rtol=1e-12,
    )
    assert [k for k, n in zip(result.kinds, negative) if n] == ["negative"] * int(negative.sum())
    assert any("not an equilibrium" in w for w in result.to_dict()["warnings"])


def test_prestressed_modes_are_paired_by_shape(cli):
    model = ancf_modal.Model.builtin("rcbo_switch_off")
    with pytest.warns(ancf_modal.ModelWarning, match="unstressed modes' state"):
        result = model.modal(prestress=True, modes=12)
    doc = result.to_dict()
    assert doc["reference_equilibrium"]["balanced"] is False
    cli_doc = cli.json("modal", "models/rcbo_switch_off.json", "--prestress", "--modes", "12")
    mine = [(m["unstressed_index"], m["mac"] is not None) for m in doc["modes"]]
    assert mine == [(m["unstressed_index"], m["mac"] is not None) for m in cli_doc["modes"]]
    for m in doc["modes"]:
        if m["unstressed_index"] is None:
            assert m["shift_percent"] is None and m["unstressed_hz"] is None
        else:
            assert m["mac"] >= 0.9
