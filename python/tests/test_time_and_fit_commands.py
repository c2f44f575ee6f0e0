"""Model.impulse, Model.transient, Model.switch_off and Model.calibrate
against the command line they front: the same document (``to_dict()`` is
``--json``, the build's version aside), the same files byte for byte, the
same keyword defaults as the flags' (``--help``), on the built-in models
and one other model file each. Runs are short (end times of a few ms at
10 µs steps)."""

import ast
import json
import pathlib
import re
import warnings

import pytest

import ancf_modal
from conftest import model_args
from test_warnings import micro


def flags(**kwargs):
    """The command line's flags for keyword arguments (``end_time=1e-3`` →
    ``--end-time 0.001``; ``True`` → the flag alone)."""
    out = []
    for key, value in kwargs.items():
        flag = "--" + key.replace("_", "-")
        if value is True:
            out.append(flag)
        elif isinstance(value, tuple):
            out += [flag, ",".join(repr(float(v)) for v in value)]
        else:
            out += [flag, str(value)]
    return out


def same_document(mine, theirs):
    """Equal documents; the provenance's `tool_version` is each build's."""
    mine, theirs = dict(mine), dict(theirs)
    assert mine.pop("tool_version") == ancf_modal.__version__
    theirs.pop("tool_version")
    assert mine.keys() == theirs.keys()
    for key in mine:
        assert mine[key] == theirs[key], key


IMPULSE = dict(end_time=5e-3, step=1e-5)


@pytest.mark.parametrize("name", ["rcbo_free_free", "cantilever"])
def test_impulse_is_the_command_lines(cli, name):
    # The assembly's hammer is a half-sine load, the cantilever's a step.
    result = ancf_modal.Model.builtin(name).impulse(**IMPULSE)
    doc = cli.json("impulse", *model_args(name), *flags(**IMPULSE))
    same_document(result.to_dict(), doc)
    assert repr(result) == cli.shown("impulse", *model_args(name), *flags(**IMPULSE))


def test_impulse_files_are_the_command_lines(cli, tmp_path):
    args = dict(end_time=5e-3, step=1e-5, sample_rate=25600.0, window="rect")
    result = ancf_modal.Model.builtin().impulse(**args)
    mine, theirs = tmp_path / "py", tmp_path / "cli"
    mine.mkdir(), theirs.mkdir()
    result.write_csv(mine / "r.csv")
    result.write_uff(mine / "r.uff")
    result.plot(mine / "r.svg")
    p = cli.run(
        "impulse", *flags(**args), "--csv", str(theirs / "r.csv"), "--uff",
        str(theirs / "r.uff"), "--plot", str(theirs / "r.svg"),
    )
    assert p.returncode == 0, p.stderr
    files = ["r.csv", "r.spectrum.csv", "r.uff", "r.svg", "r.response.svg"]
    assert sorted(f.name for f in theirs.iterdir()) == sorted(files)
    for f in files:
        assert (mine / f).read_bytes() == (theirs / f).read_bytes(), f


TRANSIENT = dict(end_time=2e-3, step=1e-5)


@pytest.mark.parametrize(
    "name, extra",
    [("rcbo_free_free", {}), ("rcbo_prestressed", {}), ("cantilever", {"from_reference": True})],
)
def test_transient_is_the_command_lines(cli, name, extra):
    args = {**TRANSIENT, **extra}
    result = ancf_modal.Model.builtin(name).transient(**args)
    same_document(result.to_dict(), cli.json("transient", *model_args(name), *flags(**args)))
    assert repr(result) == cli.shown("transient", *model_args(name), *flags(**args))


def test_transient_carries_the_models_warnings_as_the_command_line(cli, tmp_path):
    path = tmp_path / "micro.json"
    path.write_text(json.dumps(micro(150.0)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = ancf_modal.Model.from_json(str(path))
    args = dict(end_time=1e-4, step=1e-5, rigid_beams=True)
    mine = model.transient(**args).to_dict()
    assert len(mine["warnings"]) == 2
    same_document(mine, cli.json("transient", str(path), *flags(**args)))


def test_transient_files_are_the_command_lines(cli, tmp_path):
    args = dict(TRANSIENT, sample_rate=20000.0)
    result = ancf_modal.Model.builtin("cantilever").transient(**args)
    mine, theirs = tmp_path / "py", tmp_path / "cli"
    mine.mkdir(), theirs.mkdir()
    result.write_csv(mine / "t.csv")
    result.write_uff(mine / "t.uff")
    result.plot(mine / "t.svg")
    p = cli.run(
        "transient", "models/cantilever.json", *flags(**args), "--csv", str(theirs / "t.csv"),
        "--uff", str(theirs / "t.uff"), "--plot", str(theirs / "t.svg"),
    )
    assert p.returncode == 0, p.stderr
    for f in ["t.csv", "t.uff", "t.svg"]:
        assert (mine / f).read_bytes() == (theirs / f).read_bytes(), f
    every_step = ancf_modal.Model.builtin("cantilever").transient(**TRANSIENT, sample_rate=0.0)
    with pytest.raises(ancf_modal.ModelError, match="sample_rate `0`"):
        every_step.write_uff(mine / "no.uff")


SWITCH_OFF = dict(end_time=5e-4, step=1e-5)


@pytest.mark.parametrize(
    "name, extra",
    [
        ("rcbo_switch_off", {"compare_rigid": True}),
        ("cantilever", {"no_step_check": True, "direction": (0.0, -1.0), "distance": 1e-6}),
    ],
)
def test_switch_off_is_the_command_lines(cli, name, extra):
    args = {**SWITCH_OFF, **extra}
    result = ancf_modal.Model.builtin(name).switch_off(**args)
    model = [f"models/{name}.json"]
    same_document(result.to_dict(), cli.json("switch-off", *model, *flags(**args)))
    assert repr(result) == cli.shown("switch-off", *model, *flags(**args))


def test_switch_off_files_are_the_command_lines(cli, tmp_path):
    result = ancf_modal.Model.builtin("rcbo_switch_off").switch_off(**SWITCH_OFF, no_step_check=True)
    mine, theirs = tmp_path / "py", tmp_path / "cli"
    mine.mkdir(), theirs.mkdir()
    result.write_csv(mine / "s.csv")
    result.plot(mine / "s.svg")
    p = cli.run(
        "switch-off", *flags(**SWITCH_OFF, no_step_check=True), "--csv", str(theirs / "s.csv"),
        "--plot", str(theirs / "s.svg"),
    )
    assert p.returncode == 0, p.stderr
    for f in ["s.csv", "s.svg", "s.trajectory.svg"]:
        assert (mine / f).read_bytes() == (theirs / f).read_bytes(), f


def test_switch_off_settings_name_the_keyword_as_the_command_line_its_flag(cli):
    model = ancf_modal.Model.builtin("rcbo_switch_off")
    with pytest.raises(ancf_modal.ModelError) as e:
        model.switch_off(direction=(0.0, 0.0), end_time=1e-4, no_step_check=True)
    line = cli.error(
        "switch-off", "models/rcbo_switch_off.json", "--direction", "0,0", "--end-time", "1e-4",
        "--no-step-check",
    )
    assert "--direction: " in line
    assert str(e.value) == line.replace("--direction: ", "direction: ", 1)


@pytest.mark.parametrize(
    "name, target", [("rcbo_free_free", 4600.0), ("beam_free_free", 7000.0)]
)
def test_calibrate_is_the_command_lines(cli, name, target):
    result = ancf_modal.Model.builtin(name).calibrate(target_hz=target)
    args = [*model_args(name), "--target", str(target)]
    same_document(result.to_dict(), cli.json("calibrate", *args))
    assert repr(result) == cli.shown("calibrate", *args)


@pytest.mark.parametrize(
    "name, target", [("rcbo_free_free", 4600.0), ("beam_free_free", 7000.0)]
)
def test_impulse_calibration_is_the_command_lines(cli, name, target):
    experiment = dict(end_time=5e-3, step=1e-5)
    model = ancf_modal.Model.builtin(name)
    result = model.calibrate(target_hz=target, method="impulse", **experiment)
    args = [*model_args(name), "--target", str(target), "--method", "impulse", *flags(**experiment)]
    doc = cli.json("calibrate", *args)
    assert doc["method"] == "impulse"
    same_document(result.to_dict(), doc)
    # The fit reaches the target within the impulse method's tolerance.
    assert abs(result.achieved_hz[0] - target) <= 1e-3
    # The experiment of the fitted model shows the target.
    check = result.fitted_model.impulse(**experiment).first_bending[1]
    assert check == pytest.approx(target, abs=1e-3)


def test_impulse_calibration_refuses_what_it_cannot_fit(cli):
    model = ancf_modal.Model.builtin()
    with pytest.raises(ancf_modal.ModelError) as e:
        model.calibrate(target_hz=4600.0, method="impulse", mode=[2], end_time=5e-3, step=1e-5)
    line = cli.error(
        "calibrate", "--target", "4600", "--method", "impulse", "--mode", "2",
        "--end-time", "5e-3", "--step", "1e-5",
    )
    assert str(e.value) == line.replace("--method: ", "method: ", 1)
    with pytest.raises(ancf_modal.ModelError) as e:
        model.calibrate(method="impulse", end_time=1e-6, step=1e-5)
    # The library names the request's field; each front end its own name.
    assert "--" + str(e.value).replace("end_time", "end-time", 1) == cli.error(
        "calibrate", "--method", "impulse", "--end-time", "1e-6", "--step", "1e-5"
    )


def test_calibration_plot_is_the_command_lines(cli, tmp_path):
    result = ancf_modal.Model.builtin().calibrate(target_hz=4600.0)
    result.plot(tmp_path / "py.svg")
    p = cli.run("calibrate", "--target", "4600", "--plot", str(tmp_path / "cli.svg"))
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "py.svg").read_bytes() == (tmp_path / "cli.svg").read_bytes()


def help_defaults(cli, command):
    """{flag: its `[default: …]` text, or None} from `command --help`."""
    p = cli.run(command, "--help")
    assert p.returncode == 0, p.stderr
    defaults, flag = {}, None
    for line in p.stdout.splitlines():
        m = re.match(r"\s+(?:-\w, )?--([\w-]+)", line)
        if m:
            flag = m.group(1)
            defaults[flag] = None
        d = re.search(r"\[default: ([^\]]*)\]", line)
        if d and flag:
            defaults[flag] = d.group(1)
    return defaults


STUB = pathlib.Path(ancf_modal.__file__).parent / "_native.pyi"

# Keyword arguments named otherwise than their flag.
RENAMED = {"target_hz": "target", "params": "param"}


@pytest.mark.parametrize("command", ["impulse", "transient", "switch-off", "calibrate"])
def test_keyword_defaults_are_the_flags(cli, command):
    import inspect

    method = getattr(ancf_modal.Model, command.replace("-", "_"))
    parameters = list(inspect.signature(method).parameters.values())[1:]
    assert parameters, "the signature is visible (text_signature)"
    defaults = help_defaults(cli, command)
    for p in parameters:
        flag = RENAMED.get(p.name, p.name.replace("_", "-"))
        assert flag in defaults, (command, p.name)
        given = defaults[flag]
        if p.default is None or p.default is False:
            # No value, or a switch: the flag shows no default either.
            assert given is None, (flag, given)
        elif p.default is Ellipsis:
            # A default pyo3 cannot show (a tuple): the stub's comment
            # states it; the documents' equality on default runs checks it.
            stub = re.search(rf"{p.name}: .* = \.\.\.,  # (.*)", STUB.read_text())
            assert stub, p.name
            assert tuple(float(v) for v in given.split(",")) == ast.literal_eval(stub.group(1))
        elif isinstance(p.default, str):
            assert given == p.default, flag
        else:
            assert float(given) == p.default, flag
