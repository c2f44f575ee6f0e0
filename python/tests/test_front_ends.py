"""The command line and the package are two front ends over one command
layer: every subcommand has a Python counterpart, and every keyword that
names a flag has that flag's default (both come from the request's
`Default` in the library)."""

import ast
import inspect
import pathlib
import re

import pytest

import ancf_modal

# Subcommands without a Python counterpart by design.
EXEMPT = {"schema", "help"}


def subcommands(cli):
    text = cli.run("--help").stdout
    block = text.split("Commands:", 1)[1].split("Options:", 1)[0]
    return [line.split()[0] for line in block.splitlines() if line.strip()]


def counterparts(name):
    """The Python functions of subcommand `name`: the package's function or
    the model's method of the same name (`-` as `_`); `frf` also reads
    files (`frf_files`)."""
    py = name.replace("-", "_")
    found = [f for f in (getattr(ancf_modal, py, None), getattr(ancf_modal.Model, py, None)) if f]
    if name == "frf":
        found.append(ancf_modal.frf_files)
    return found


def test_every_subcommand_has_a_python_counterpart(cli):
    names = subcommands(cli)
    assert {"modal", "static", "frf", "sweep"} <= set(names), names
    missing = [n for n in names if n not in EXEMPT and not counterparts(n)]
    assert missing == []


def flag_defaults(cli, name):
    """`--flag`: default text, from `ancf-modal NAME --help`."""
    text = cli.run(name, "--help").stdout
    out = {}
    for m in re.finditer(r"--([a-z0-9-]+)[^\n]*?(?:\n(?!\s*-)[^\n]*)*?\[default: ([^\]]+)\]", text):
        out[m.group(1)] = m.group(2)
    return out


def stub_defaults():
    """`(owner, function) -> {keyword: default}` from the stub `_native.pyi`
    (owner `None` for module functions)."""
    text = (pathlib.Path(ancf_modal.__file__).parent / "_native.pyi").read_text()
    lines = text.splitlines()
    tree = ast.parse(text)
    out = {}

    def value(d):
        # A default pyo3 cannot show is `...` in the stub too, with its
        # value in a comment: `direction: Tuple[float, float] = ...,  # (1.0, 0.0)`.
        if isinstance(d, ast.Constant) and d.value is ...:
            line = lines[d.lineno - 1]
            return ast.literal_eval(line.split("#", 1)[1].strip()) if "#" in line else ...
        return ast.literal_eval(d)

    def add(owner, f):
        args = f.args.args + f.args.kwonlyargs
        defaults = [None] * (len(f.args.args) - len(f.args.defaults)) + f.args.defaults
        defaults += f.args.kw_defaults
        out[(owner, f.name)] = {
            a.arg: value(d) for a, d in zip(args, defaults) if d is not None
        }

    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            add(None, node)
        elif isinstance(node, ast.ClassDef):
            for f in node.body:
                if isinstance(f, ast.FunctionDef):
                    add(node.name, f)
    return out


def same(python_default, cli_text):
    if isinstance(python_default, (tuple, list)):
        return [float(v) for v in cli_text.split(",")] == [float(v) for v in python_default]
    if isinstance(python_default, bool) or python_default is None:
        return str(python_default).lower() == cli_text.lower()
    if isinstance(python_default, (int, float)):
        return float(python_default) == float(cli_text)
    return str(python_default) == cli_text


@pytest.mark.parametrize("name", ["modal", "static", "impulse", "transient", "switch-off", "calibrate", "convergence", "sweep", "frf", "identify", "report"])
def test_python_defaults_are_the_flags_defaults(cli, name):
    flags = flag_defaults(cli, name)
    functions = counterparts(name)
    if not functions:
        pytest.fail(f"no Python counterpart of `{name}`")
    stub = stub_defaults()
    compared = 0
    for f in functions:
        owner = "Model" if getattr(ancf_modal.Model, f.__name__, None) is f else None
        in_stub = stub.get((owner, f.__name__), {})
        for p in inspect.signature(f).parameters.values():
            flag = p.name.replace("_", "-")
            if p.default is inspect.Parameter.empty or flag not in flags:
                continue
            # The stub holds what pyo3 cannot show (a tuple shows as `...`),
            # and must agree with the runtime where both show it.
            default = in_stub.get(p.name, p.default) if p.default is ... else p.default
            if p.default is not ... and p.name in in_stub:
                assert same(in_stub[p.name], flags[flag]), ("stub", name, p.name, in_stub[p.name], flags[flag])
            compared += 1
            assert same(default, flags[flag]), (name, p.name, default, flags[flag])
    if flags:
        assert compared > 0, (name, flags)
