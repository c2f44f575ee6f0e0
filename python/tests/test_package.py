"""The package itself: version, shipped models, stubs, typing marker."""

import os
import pathlib
import subprocess
import sys

import ancf_modal
from conftest import MODELS


def test_version_is_the_command_lines(cli):
    assert ancf_modal.__version__ == cli.json("modal", "--modes", "3")["tool_version"]


def test_every_shipped_model_is_built_in():
    stems = sorted(p.stem for p in MODELS.glob("*.json"))
    assert sorted(ancf_modal.Model.builtin_names()) == stems
    for stem in stems:
        model = ancf_modal.Model.builtin(stem)
        text = (MODELS / f"{stem}.json").read_text()
        # The same bytes as the file: the same model_sha256 as the command line.
        import hashlib

        assert model.sha256 == hashlib.sha256(text.encode()).hexdigest()


def test_typed_package():
    package = pathlib.Path(ancf_modal.__file__).parent
    assert (package / "py.typed").exists()
    assert (package / "_native.pyi").exists()


def test_stubs_match_the_module():
    p = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "ancf_modal._native"],
        capture_output=True,
        text=True,
        env={**os.environ, "MYPY_CACHE_DIR": os.devnull},
    )
    assert p.returncode == 0, p.stdout + p.stderr
