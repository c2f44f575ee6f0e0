"""Warnings reach Python three times, as the command line gives them: raised
with ``warnings.warn`` as ``ancf_modal.ModelWarning`` (a ``UserWarning``) at
the user's call that gave them, kept in the result documents' ``warnings``
(``to_dict()``) and listed at the end of the ``repr``, the same text as the
command line's ``warning:`` lines. The cases: a model whose part sizes
disagree by orders of magnitude (a 150 µm arm typed as 150 among micrometre
parts), a steel cantilever whose section height is typed in metres where
millimetres were meant, and the UFF datasets ``frf_files`` skipped
(Simcenter Testlab's 1858 qualifiers beside an FRF; pyuff's sample
``tests/data/pyuff/1858.uff``, MIT)."""

import inspect
import json
import math
import warnings

import numpy as np
import pytest

import ancf_modal
from conftest import ROOT


def micro(arm):
    """A 200 µm base clamped at the ground, an arm welded to its tip and a
    200 µm mass (√(I/m) = 200 µm) welded to the arm's tip without `local`;
    lengths in metres, the arm's given by `arm`."""

    def beam(id, start, length):
        return {
            "id": id,
            "start": [start, 0.0],
            "angle_deg": 0.0,
            "length": length,
            "elements": 4,
            "section": {"height": 5e-6, "width": 10e-6},
            "material": {"young": 160e9, "density": 2330.0},
        }

    return {
        "name": "micro",
        "beams": [beam("base", 0.0, 200e-6), beam("arm", 200e-6, arm)],
        "rigid_bodies": [
            {"id": "mass", "mass": 1e-9, "inertia": 4e-17, "position": [350e-6, 0.0]}
        ],
        "joints": [
            {"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "base", "s": 0.0}},
            {"type": "weld", "a": {"beam": "base", "s": 200e-6}, "b": {"beam": "arm", "s": 0.0}},
            {"type": "weld", "a": {"beam": "arm", "s": arm}, "b": {"body": "mass"}},
        ],
    }


def test_consistent_sizes_raise_no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ancf_modal.Model.from_json(json.dumps(micro(150e-6)))


def test_sizes_that_disagree_are_python_warnings_and_in_the_document(tmp_path, cli):
    path = tmp_path / "micro.json"
    path.write_text(json.dumps(micro(150.0)))
    with pytest.warns(ancf_modal.ModelWarning) as record:
        model = ancf_modal.Model.from_json(str(path))
    texts = [str(w.message) for w in record]
    assert len(texts) == 2, texts
    assert texts[0].startswith(f"{path}: beams[1].length: beam `arm` (length 150 m)")
    assert texts[1].startswith(f"{path}: joints[2].b: ") and "rigid body `mass`" in texts[1]
    doc = model.modal(modes=3).to_dict()
    assert doc["warnings"][:2] == texts
    # The command line's document carries the same warnings.
    assert cli.json("modal", str(path), "--modes", "3")["warnings"] == doc["warnings"]
    # A model changed into the same disagreement warns again.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fine = ancf_modal.Model.from_json(json.dumps(micro(150e-6)))
    with pytest.warns(ancf_modal.ModelWarning, match="beam `arm`"):
        fine.with_params({"beams[arm].length": 150.0})


def write_hit(path):
    """A hammer hit on a 180 Hz, 1 % oscillator: force (half-sine, 0.5 ms)
    and velocity, sampled at 10240 Hz for 1 s."""
    fs, fn, zeta = 10240.0, 180.0, 0.01
    t = np.arange(int(fs)) / fs
    force = np.where(t < 5e-4, 100.0 * np.sin(np.pi * t / 5e-4), 0.0)
    w = 2 * math.pi * fn
    velocity = np.exp(-zeta * w * t) * np.cos(w * math.sqrt(1 - zeta**2) * t) * 1e-3
    with open(path, "w") as f:
        f.write("time,force,velocity\n")
        for row in zip(t, force, velocity):
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def test_skipped_uff_datasets_are_a_python_warning(tmp_path, cli):
    csv = tmp_path / "hit.csv"
    write_hit(csv)
    alone = tmp_path / "h.uff"
    p = cli.run("frf", str(csv), "--uff", str(alone))
    assert p.returncode == 0, p.stderr
    mixed = tmp_path / "mixed.uff"
    qualifiers = (ROOT / "tests" / "data" / "pyuff" / "1858.uff").read_bytes()
    mixed.write_bytes(alone.read_bytes() + qualifiers)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        a = ancf_modal.frf_files([alone])
    with pytest.warns(ancf_modal.ModelWarning) as record:
        b = ancf_modal.frf_files([mixed])
    texts = [str(w.message) for w in record]
    assert len(texts) == 1 and texts[0].startswith(f"{mixed}: 2 UFF datasets"), texts
    assert "1858 ×2 (first at line" in texts[0]
    da, db = a.to_dict(), b.to_dict()
    assert da.pop("warnings") == [] and db.pop("warnings") == texts
    assert da.pop("files") == [str(alone)] and db.pop("files") == [str(mixed)]
    assert da == db, "the FRF reads as alone"
    assert cli.json("frf", str(mixed))["warnings"] == texts
    # The repr is the command line's table and its warning line.
    assert repr(b) == cli.shown("frf", str(mixed))
    assert repr(b).splitlines()[-1] == "warning: " + texts[0]
    assert "warning:" not in repr(a)


def test_one_category_a_user_warning():
    assert issubclass(ancf_modal.ModelWarning, UserWarning)
    assert ancf_modal.ModelWarning.__module__ == "ancf_modal"
    assert not issubclass(ancf_modal.ModelWarning, RuntimeWarning)


def steel_cantilever(height):
    """A steel cantilever 40 mm long, 5 mm wide, clamped at s = 0; `height`
    [m] is the section's bending-plane size."""
    return {
        "name": "steel cantilever",
        "beams": [
            {
                "id": "blade",
                "start": [0.0, 0.0],
                "angle_deg": 0.0,
                "length": 40e-3,
                "elements": 8,
                "section": {"height": height, "width": 5e-3},
                "material": {"young": 210e9, "density": 7850.0},
            }
        ],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [0.0, 0.0]},
             "b": {"beam": "blade", "s": 0.0}}
        ],
    }


def test_a_height_in_metres_warns_at_modal_and_in_the_repr(tmp_path, cli):
    # 0.5 typed where 0.5 mm was meant: 12.5 times the length. Reading it
    # says so (a unit warning) ...
    path = tmp_path / "steel.json"
    path.write_text(json.dumps(steel_cantilever(0.5)))
    with pytest.warns(ancf_modal.ModelWarning, match=r"height/length = 12\.500 is above 0\.1"):
        model = ancf_modal.Model.from_json(str(path))
    unit = f"{path}: beams[0].section.height: height/length = 12.500"
    assert repr(model).splitlines()[0] == f'<ancf_modal.Model "steel cantilever" from {path}>'
    assert repr(model).splitlines()[1].startswith("warning: " + unit)
    # ... and `modal` gives its own: the one bending mode among the first
    # 12 is past beam theory (Timoshenko would lower it by more than half).
    with pytest.warns(ancf_modal.ModelWarning) as record:
        result = model.modal(modes=12)
    texts = [str(w.message) for w in record]
    assert all(w.category is ancf_modal.ModelWarning for w in record)
    assert all(w.filename == __file__ for w in record), [w.filename for w in record]
    assert len(texts) == 1, texts
    assert texts[0].startswith(f"{path}: mode 5 (261099.5 Hz): beam theory does not hold for it: "
                               "shear and rotary inertia (Timoshenko) would lower it by more than half")
    assert result.kinds[4] == "bending"
    doc = result.to_dict()
    assert doc["warnings"][1:] == texts and doc["warnings"][0].startswith(unit)
    # The repr lists both, after the table, as the command line's terminal.
    lines = repr(result).splitlines()
    assert lines[-2:] == ["warning: " + w for w in doc["warnings"]]
    assert repr(result) == cli.shown("modal", str(path), "--modes", "12")
    # The height meant (0.5 mm) warns of neither.
    with warnings.catch_warnings(record=True) as fixed_record:
        warnings.simplefilter("always")
        fixed = model.with_params({"beams[blade].section.height": 0.5e-3})
        fixed.modal(modes=12)
    fixed_texts = [str(w.message) for w in fixed_record]
    assert not any("height/length" in t or "does not hold" in t for t in fixed_texts), fixed_texts


def test_a_warning_points_at_the_callers_line(tmp_path):
    # The record's file and line are the call in this file (stack level:
    # the frame that called the extension), not the package's internals.
    path = tmp_path / "steel.json"
    path.write_text(json.dumps(steel_cantilever(0.5)))
    calls = {}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        calls["from_json"] = inspect.currentframe().f_lineno + 1
        model = ancf_modal.Model.from_json(str(path))
        calls["modal"] = inspect.currentframe().f_lineno + 1
        model.modal(modes=12)
        calls["with_params"] = inspect.currentframe().f_lineno + 1
        model.with_params({"beams[blade].section.width": 6e-3})
    assert len(caught) == 3, [str(w.message) for w in caught]
    assert [(w.filename, w.lineno) for w in caught] == [(__file__, n) for n in calls.values()]
    assert all(w.category is ancf_modal.ModelWarning for w in caught)
    texts = [str(w.message) for w in caught]
    assert "height/length" in texts[0] and "height/length" in texts[2]
    assert "Timoshenko" in texts[1]


def warning_lines(result):
    """The `warning:` lines of a result's repr, without `warning: `."""
    return [l[len("warning: "):] for l in repr(result).splitlines() if l.startswith("warning: ")]


def test_every_results_repr_lists_its_warnings(tmp_path):
    path = tmp_path / "micro.json"
    path.write_text(json.dumps(micro(150.0)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = ancf_modal.Model.from_json(str(path))
        results = {
            "static": model.static(),
            "transient": model.transient(end_time=1e-4, step=1e-5, rigid_beams=True),
            "switch_off": model.switch_off(end_time=1e-4, step=1e-5, point="mass",
                                           no_step_check=True),
            "convergence": model.convergence(max_elements=8, modes=1),
            "sweep": ancf_modal.sweep(model, {"beams[arm].section.height": (4e-6, 6e-6, 2)},
                                      "first_bending_hz"),
        }
    for name, result in results.items():
        doc = result.to_dict()["warnings"]
        assert len(doc) >= 2, (name, doc)
        assert warning_lines(result) == doc, name
        assert repr(result).endswith("".join(f"warning: {w}\n" for w in doc)), name
    # A time-domain run's own warning (not the model's): raised and listed.
    with pytest.warns(ancf_modal.ModelWarning) as record:
        hit = ancf_modal.Model.builtin("cantilever").impulse(end_time=5e-3, step=1e-5)
    own = hit.to_dict()["warnings"]
    assert len(own) == 1 and [str(w.message) for w in record] == own
    assert warning_lines(hit) == own
    # The model's repr lists its unit warnings; a model without any, none.
    assert warning_lines(model) == results["static"].to_dict()["warnings"]
    clean = ancf_modal.Model.builtin("cantilever")
    assert repr(clean) == '<ancf_modal.Model "cantilever" from models/cantilever.json>'
    assert "warning:" not in repr(clean.static())
