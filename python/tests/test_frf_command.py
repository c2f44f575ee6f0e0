"""`frf` from Python against the command line: the same hammer record as
arrays (``ancf_modal.frf``) and as a file (``ancf_modal.frf_files``) gives
the document ``frf --json`` prints, and ``FrfResult.write_uff``,
``write_csv`` and ``plot`` write the bytes of ``frf --uff``, ``--csv`` and
``--plot``; with ``model`` and ``at`` the model's FRF is in both."""

import math

import numpy as np
import pytest

import ancf_modal
from conftest import MODELS

# A power of two: the time column k/FS is exact in a CSV file, so the
# rate the command line reads from it is FS itself and the arrays and the
# file are the same record, bit for bit.
FS = 8192.0
F_N, ZETA = 180.0, 0.01


def hammer_hit(seed, seconds=1.0):
    """Force [N] (a 0.5 ms half-sine) and velocity [m/s] of a 1 kg
    mass–spring–damper (f_n = 180 Hz, ζ = 1 %), with 0.05 % noise."""
    n = int(seconds * FS)
    t = np.arange(n) / FS
    force = np.where(t < 5e-4, 100.0 * np.sin(np.pi * t / 5e-4), 0.0)
    w = 2 * math.pi * F_N
    wd = w * math.sqrt(1 - ZETA**2)
    velocity = np.zeros(n)
    for k in np.nonzero(force)[0]:
        tau = t[k:] - t[k]
        unit = np.exp(-ZETA * w * tau) * (np.cos(wd * tau) - ZETA * w / wd * np.sin(wd * tau))
        velocity[k:] += force[k] / FS * unit
    rng = np.random.default_rng(seed)
    velocity += 5e-4 * np.max(np.abs(velocity)) * rng.standard_normal(n)
    return t, force, velocity


def write_csv(path, t, force, response):
    with open(path, "w") as f:
        f.write("time,force,response\n")
        for row in zip(t, force, response):
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def without_version(doc):
    doc = dict(doc)
    doc.pop("tool_version")
    return doc


@pytest.mark.parametrize("hits", [1, 2])
def test_arrays_and_files_give_the_command_lines_document(tmp_path, cli, hits):
    records = [hammer_hit(seed=s) for s in range(hits)]
    paths = []
    for i, (t, f, v) in enumerate(records):
        paths.append(str(tmp_path / f"hit{i}.csv"))
        write_csv(paths[-1], t, f, v)
    doc = without_version(cli.json("frf", *paths, "--band", "50:1000"))
    assert doc["model_sha256"] is None and doc["averages"] == hits
    files = without_version(ancf_modal.frf_files(paths, band=(50.0, 1000.0)).to_dict())
    assert files == doc
    force = np.array([f for _, f, _ in records])
    velocity = np.array([v for _, _, v in records])
    if hits == 1:
        force, velocity = force[0], velocity[0]
    arrays = without_version(ancf_modal.frf(force, velocity, FS, band=(50.0, 1000.0)).to_dict())
    # The arrays have no file names; all else is the command line's.
    names = ["<array>"] if hits == 1 else [f"<array row {i}>" for i in range(hits)]
    assert arrays.pop("files") == names
    doc.pop("files")
    assert arrays == doc


def test_written_files_are_the_command_lines(tmp_path, cli):
    t, f, v = hammer_hit(seed=7)
    path = str(tmp_path / "hit.csv")
    write_csv(path, t, f, v)
    flags = ["--window", "force:0.05", "--response-quantity", "velocity"]
    outputs = {
        "--uff": tmp_path / "cli.uff",
        "--csv": tmp_path / "cli.csv",
        "--plot": tmp_path / "cli.svg",
    }
    args = [a for flag, p in outputs.items() for a in (flag, str(p))]
    p = cli.run("frf", path, *flags, *args)
    assert p.returncode == 0, p.stderr
    r = ancf_modal.frf_files([path], window="force:0.05", response_quantity="velocity")
    r.write_uff(tmp_path / "py.uff")
    r.write_csv(tmp_path / "py.csv")
    r.plot(tmp_path / "py.svg")
    for ext in ("uff", "csv", "svg"):
        mine = (tmp_path / f"py.{ext}").read_bytes()
        assert mine == (tmp_path / f"cli.{ext}").read_bytes(), ext
    # The arrays' UFF differs from the file's in its ID line naming the
    # record only.
    a = ancf_modal.frf(f, v, FS, window="force:0.05")
    a.write_uff(tmp_path / "arrays.uff")
    mine = (tmp_path / "arrays.uff").read_text().splitlines()
    theirs = (tmp_path / "cli.uff").read_text().splitlines()
    differ = [i for i, (x, y) in enumerate(zip(mine, theirs)) if x != y]
    assert len(mine) == len(theirs) and len(differ) == 2, differ  # H1's and γ²'s ID line 4
    assert all(mine[i].strip() == "<array>" for i in differ)


def test_the_model_overlay_is_the_command_lines(tmp_path, cli):
    sig = tmp_path / "sig.csv"
    model_path = str(MODELS / "rcbo_free_free.json")
    p = cli.run("impulse", model_path, "--end-time", "0.02", "--csv", str(sig))
    assert p.returncode == 0, p.stderr
    flags = ["--force", "force_n", "--response", "vibrometer_velocity"]
    doc = cli.json("frf", str(sig), *flags, "--window", "exponential:0.01",
                   "--model", model_path, "--at", "vibrometer")
    model = ancf_modal.Model.from_json(model_path)
    r = ancf_modal.frf_files([sig], force="force_n", response="vibrometer_velocity",
                             window="exponential:0.01", model=model, at="vibrometer")
    assert without_version(r.to_dict()) == without_version(doc)
    assert doc["model_sha256"] == model.sha256
    h = np.array([complex(*c) for c in doc["model_frf"]["h"]])
    assert np.array_equal(r.model_frf, h)
    assert ancf_modal.frf_files([sig], force="force_n", response="vibrometer_velocity").model_frf is None
    with pytest.raises(ancf_modal.ModelError, match=r"^at `none`"):
        ancf_modal.frf_files([sig], force="force_n", model=model)
    with pytest.raises(ancf_modal.ModelError, match=r"no sensor `nowhere`"):
        ancf_modal.frf_files([sig], force="force_n", model=model, at="nowhere")


def help_defaults(cli, command):
    """{flag without dashes, with underscores: default} of `command --help`."""
    import re

    p = cli.run(command, "--help")
    assert p.returncode == 0, p.stderr
    # Each option with its help, on its line or on the lines after it.
    found, flag = {}, None
    for line in p.stdout.splitlines():
        m = re.match(r"^\s+(?:-\w, )?--([a-z-]+)", line)
        if m:
            flag = m.group(1).replace("-", "_")
        default = re.search(r"\[default: ([^\]]+)\]", line)
        if default and flag:
            found[flag] = default.group(1)
    return found


@pytest.mark.parametrize(
    "command, function",
    [
        ("frf", ancf_modal.frf),
        ("frf", ancf_modal.frf_files),
        ("identify", ancf_modal.Model.identify),
    ],
)
def test_keyword_defaults_are_the_command_lines(cli, command, function):
    import inspect

    defaults = help_defaults(cli, command)
    assert defaults, command
    parameters = inspect.signature(function).parameters
    compared = 0
    for name, text in defaults.items():
        if name not in parameters:
            continue
        mine = parameters[name].default
        if isinstance(mine, bool):
            assert str(mine).lower() == text, name
        elif isinstance(mine, (int, float)):
            assert mine == float(text), name
        else:
            assert mine == text, name
        compared += 1
    # Every flag with a default has its keyword (Python passes arrays' `fs`
    # and files' `paths` instead of the positional SIGNALS).
    assert compared == len(defaults), (defaults, list(parameters))
