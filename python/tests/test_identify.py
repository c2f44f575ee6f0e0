"""`Model.identify` against the command line's `identify`: the same
document as ``identify --json`` on the built-in model and on another
shipped model (with measured records), and ``write_out_dir`` writes the
files of ``identify --out-dir`` byte for byte."""

import json
import warnings

import numpy as np
import pytest

import ancf_modal
from conftest import model_args


def without_version(doc):
    doc = dict(doc)
    doc.pop("tool_version")
    return doc


def test_builtin_model_gives_the_command_lines_document_and_files(tmp_path, cli):
    out = tmp_path / "cli"
    p = cli.run("identify", "--end-time", "0.01", "--calibrate", "--out-dir", str(out))
    assert p.returncode == 0, p.stderr
    doc = cli.json("identify", "--end-time", "0.01", "--calibrate")
    # No note on records (none given): only the modal analysis's own
    # warnings, as `modal` raises them, and the document's.
    with pytest.warns(ancf_modal.ModelWarning) as caught:
        r = ancf_modal.Model.builtin().identify(end_time=0.01, calibrate=True)
    assert [str(w.message) for w in caught] == doc["warnings"]
    assert all("beam theory" in w for w in doc["warnings"]), doc["warnings"]
    assert without_version(r.to_dict()) == without_version(doc)
    # The paper's Table 3: the experiment is the paper's 4600 Hz.
    assert r.paper and r.experiment_hz == doc["experiment_hz"] == 4600.0
    assert r.table == doc["table"]
    assert r.frequencies_hz.shape == (12,)
    # The calibrated model meets the experiment with its eigenvalue.
    fitted = r.calibrated_model.modal(modes=12)
    bending = [f for f, k in zip(fitted.frequencies_hz, fitted.kinds) if k == "bending"]
    assert abs(bending[0] - 4600.0) < 0.01
    mine = tmp_path / "py"
    r.write_out_dir(mine)
    names = sorted(f.name for f in out.iterdir())
    assert sorted(f.name for f in mine.iterdir()) == names
    assert "calibrated.json" in names and "summary.json" in names
    for name in names:
        assert (mine / name).read_bytes() == (out / name).read_bytes(), name
    assert repr(r).startswith("model ") and "paper Table 3" in repr(r)


def test_another_model_with_measured_records(tmp_path, cli):
    sig = tmp_path / "sig.csv"
    # The paper's assembly's hammer test, as measured records.
    p = cli.run("impulse", "--end-time", "0.05", "--csv", str(sig))
    assert p.returncode == 0, p.stderr
    flags = ["--end-time", "0.01", "--sample-rate", "0", "--window", "rect"]
    measured = ["--measured", str(sig), "--measured-window", "hann"]
    # The cantilever 2.8² times lighter: f₁ = 2.8 × 1071.5 = 3000 Hz, f₂ =
    # 6.27 f₁ = 18.8 kHz, so the records' mode (4568.6 Hz) is its first
    # bending's (the cantilever itself has f₂ = 6716 Hz, nearer the records'
    # mode than its f₁: that mode would measure its second).
    light = json.loads(ancf_modal.Model.builtin("cantilever").to_json())
    light["beams"][0]["material"]["density"] = 8940.0 / (2.8 * 2.8)
    path = tmp_path / "light_cantilever.json"
    path.write_text(json.dumps(light))
    doc = cli.json("identify", str(path), *flags, *measured)
    model = ancf_modal.Model.from_json(str(path))
    # The taper on the records is warned of, as `frf_files` warns of it.
    with pytest.warns(ancf_modal.ModelWarning, match="hann window tapers the blow"):
        r = model.identify(end_time=0.01, sample_rate=0.0, window="rect",
                           measured=[sig], measured_window="hann")
    mine = r.to_dict()
    assert without_version(mine) == without_version(doc)
    assert mine["measured"]["files"] == [str(sig)]
    # The records' notes besides the analyses' warnings (beam theory, and
    # the impulse's: a 10 ms run holds too few periods).
    notes = [w for w in mine["warnings"]
             if "beam theory limits it" not in w and "periods of the first bending mode" not in w]
    # The hann window's taper note, and that its fit found no mode to
    # compare with.
    assert len(notes) == 2 and not r.paper
    assert any("tapers the blow" in w for w in notes)
    assert any("found no mode over" in w for w in notes)
    assert r.experiment_hz is None
    # The window and band of the records are --measured-window and
    # --measured-band: the fitted mode is the experiment.
    measured = ["--measured", str(sig), "--measured-window", "exponential:0.01",
                "--measured-band", "3000:6000"]
    banded = cli.json("identify", str(path), *flags, *measured)
    with pytest.warns(ancf_modal.ModelWarning) as caught:
        r = model.identify(end_time=0.01, sample_rate=0.0, window="rect", measured=[sig],
                           measured_window="exponential:0.01", measured_band=(3000.0, 6000.0))
    assert without_version(r.to_dict()) == without_version(banded)
    # No note on these records: the warnings are the analyses' (the modal
    # analysis's beam theory, the impulse's short run).
    assert [str(w.message) for w in caught] == banded["warnings"]
    assert all("beam theory limits it" in w or "periods of the first bending mode" in w
               for w in banded["warnings"])
    assert r.experiment_hz == banded["experiment_hz"]
    assert abs(r.experiment_hz - 4568.6) < 1.0
    assert np.allclose(r.to_dict()["measured"]["band_hz"], [3000.0, 6000.0])


def test_bad_arguments_are_model_errors():
    model = ancf_modal.Model.builtin()
    with pytest.raises(ancf_modal.ModelError, match=r"^step `-0.000001`: must be a number > 0"):
        model.identify(step=-1e-6)
    with pytest.raises(ancf_modal.ModelError, match=r"^measured_window `kaiser`"):
        model.identify(measured_window="kaiser")
    with pytest.raises(ancf_modal.ModelError, match=r"^end_time `0.0000001`: must be longer than one step \(0.000001 s\)"):
        model.identify(end_time=1e-7)
    with pytest.raises(ancf_modal.ModelError, match=r"calibrate needs an experiment"):
        ancf_modal.Model.builtin("cantilever").identify(end_time=0.005, calibrate=True)


def test_identify_gives_the_modal_analysis_warnings_modal_gives(cli):
    # The first outside-eyes trial of the command layer: `identify` dropped
    # the beam-theory warnings `modal` gives on the same model and modes.
    model = ancf_modal.Model.builtin("cantilever")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        modal = model.modal(modes=12).to_dict()["warnings"]
        identified = model.identify(end_time=0.005, step=1e-5).to_dict()["warnings"]
    beam_theory = [w for w in modal if "beam theory limits it" in w]
    assert beam_theory, modal
    assert all(w in identified for w in beam_theory), (beam_theory, identified)
    doc = cli.json("identify", "models/cantilever.json", "--end-time", "0.005", "--step", "1e-5")
    assert doc["warnings"] == identified
