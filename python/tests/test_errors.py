"""Errors are Python exceptions carrying the command line's one-line message."""

import json

import pytest

import ancf_modal


def test_exception_classes():
    assert issubclass(ancf_modal.ModelError, ValueError)
    assert issubclass(ancf_modal.AnalysisError, RuntimeError)
    assert not issubclass(ancf_modal.ModelError, RuntimeError)


def bad_model(tmp_path, cli):
    doc = json.loads(ancf_modal.Model.builtin("beam_free_free").to_json())
    doc["beams"][0]["section"]["height"] = -1e-3
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(doc, indent=2))
    return path


def test_invalid_model_file(tmp_path, cli):
    path = bad_model(tmp_path, cli)
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.Model.from_json(str(path))
    assert str(e.value) == cli.error("modal", str(path))
    assert "section.height" in str(e.value)


def test_malformed_json_file(tmp_path, cli):
    path = tmp_path / "broken.json"
    path.write_text('{"name": "x", "beams": [}')
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.Model.from_json(path)
    assert str(e.value) == cli.error("modal", str(path))


def test_missing_file(tmp_path, cli):
    path = tmp_path / "missing.json"
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.Model.from_json(str(path))
    assert str(e.value) == cli.error("modal", str(path))


def test_json_text_is_named_as_such():
    with pytest.raises(ancf_modal.ModelError, match=r"^<json text>:1:\d+: malformed JSON"):
        ancf_modal.Model.from_json("{ nonsense")


def test_unknown_parameter(cli):
    model = ancf_modal.Model.builtin()
    with pytest.raises(ancf_modal.ModelError) as e:
        model.with_params({"no_such_parameter": 1.0})
    expected = cli.error(
        "sweep", "--param", "no_such_parameter=1:1:1", "--quantity", "first_bending_hz"
    )
    # The command line names its flag, the package its argument.
    assert str(e.value) == expected.replace("--param: ", "params: ", 1)


def test_parameter_value_the_model_refuses():
    model = ancf_modal.Model.builtin()
    with pytest.raises(ancf_modal.ModelError, match=r"section\.height: must be positive"):
        model.with_params({"height": -1e-3})


@pytest.mark.parametrize(
    "kwargs, flag",
    [({"modes": 0}, ("--modes", "0")), ({"solver": "qz"}, ("--solver", "qz"))],
)
def test_bad_argument_value(cli, kwargs, flag):
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.Model.builtin().modal(**kwargs)
    (name, value) = next(iter(kwargs.items()))
    message = str(e.value)
    assert message.startswith(f"{name} `{value}`: ")
    if name == "modes":
        # The command line states the same range for its flag.
        assert message == cli.error("modal", *flag).replace("--modes", "modes", 1)


def test_unknown_builtin_lists_the_names():
    with pytest.raises(ancf_modal.ModelError) as e:
        ancf_modal.Model.builtin("nope")
    for name in ancf_modal.Model.builtin_names():
        assert name in str(e.value)


def test_analysis_failure_is_an_analysis_error(cli):
    # A load on a free assembly has nothing to react it: no static
    # equilibrium, so no pre-stressed modes.
    doc = json.loads(ancf_modal.Model.builtin("beam_free_free").to_json())
    beam = doc["beams"][0]
    doc["loads"] = [
        {"at": {"beam": beam["id"], "s": beam["length"]}, "force": [0.0, 1.0]}
    ]
    model = ancf_modal.Model.from_json(json.dumps(doc))
    with pytest.raises(ancf_modal.AnalysisError) as e:
        model.modal(prestress=True)
    assert str(e.value).startswith("<json text>: ")
    assert "support" in str(e.value)


def test_a_panic_is_an_analysis_error():
    from ancf_modal import _native

    with pytest.raises(ancf_modal.AnalysisError, match="internal error.*a test panic"):
        _native._panic("a test panic")
    # The module still works after it.
    assert ancf_modal.Model.builtin().modal(modes=4).rigid_modes == 3
