"""Shared fixtures: the repository's paths and the command line to compare with."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
MODELS = ROOT / "models"


def _binary() -> str:
    given = os.environ.get("ANCF_MODAL_BIN")
    if given:
        return given
    return str(ROOT / "target" / "release" / "ancf-modal")


class Cli:
    """Runs `ancf-modal` from the repository root (so that relative model
    paths read as the package's built-in models name them)."""

    def __init__(self, binary: str):
        self.binary = binary

    def run(self, *args: str) -> subprocess.CompletedProcess:
        return subprocess.run(
            [self.binary, *args], cwd=ROOT, capture_output=True, text=True, check=False
        )

    def json(self, *args: str) -> dict:
        p = self.run(*args, "--json")
        assert p.returncode == 0, p.stderr
        return json.loads(p.stdout)

    def shown(self, *args: str) -> str:
        """What a successful run shows on a terminal: its report (stdout),
        then its `warning:` lines (stderr), as a result's `repr` shows
        them."""
        p = self.run(*args)
        assert p.returncode == 0, p.stderr
        lines = [l + "\n" for l in p.stderr.splitlines() if l.startswith("warning: ")]
        return p.stdout + "".join(lines)

    def error(self, *args: str) -> str:
        """The one `Error:` line of a failing run, without `Error: `."""
        p = self.run(*args)
        assert p.returncode == 1, (p.returncode, p.stdout, p.stderr)
        lines = [l for l in p.stderr.splitlines() if l.startswith("Error: ")]
        assert len(lines) == 1, p.stderr
        return lines[0][len("Error: ") :]


@pytest.fixture(scope="session")
def cli() -> Cli:
    binary = _binary()
    if not os.access(binary, os.X_OK):
        pytest.fail(f"no ancf-modal binary at {binary}: run `cargo test --release` first")
    return Cli(binary)


def model_args(name: str) -> list:
    """The command line's model argument for the shipped model `name`, as
    `Model.builtin(name)` names its source: none for the built-in default,
    else the file relative to the repository root."""
    return [] if name == "rcbo_free_free" else [f"models/{name}.json"]


def close_documents(mine, theirs, rtol=1e-12):
    """Every value of `mine` equals `theirs`' (numbers to rtol)."""
    if isinstance(mine, dict):
        for key, value in mine.items():
            assert key in theirs, key
            close_documents(value, theirs[key], rtol)
    elif isinstance(mine, list):
        assert len(mine) == len(theirs)
        for a, b in zip(mine, theirs):
            close_documents(a, b, rtol)
    elif isinstance(mine, float) and isinstance(theirs, float):
        assert abs(mine - theirs) <= rtol * max(abs(theirs), 1e-300) or mine == theirs
    else:
        assert mine == theirs
