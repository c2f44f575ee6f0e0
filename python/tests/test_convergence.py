"""`Model.convergence` against the command line's `convergence --json` and
against the order of accuracy Hermite cubics must show."""

import json
import math

import numpy as np
import pytest

import ancf_modal
from conftest import model_args


@pytest.mark.parametrize("name", ["rcbo_free_free", "beam_free_free"])
def test_document_equals_the_command_line(cli, name):
    result = ancf_modal.Model.builtin(name).convergence(max_elements=16, modes=2)
    doc = cli.json("convergence", *model_args(name), "--max-elements", "16", "--modes", "2")
    assert result.to_dict() == doc
    assert result.elements == doc["elements"]
    assert np.array_equal(result.frequencies_hz, np.array(doc["frequencies_hz"]))


def test_free_beam_converges_at_fourth_order_to_euler_bernoulli():
    # A single free-free beam: the reference is Euler–Bernoulli's
    # f = (βL)²/(2πL²)·√(EI/ρA), computed here from the model file.
    model = ancf_modal.Model.builtin("beam_free_free")
    beam = json.loads(model.to_json())["beams"][0]
    length = beam["length"]
    h, b = beam["section"]["height"], beam["section"]["width"]
    e, rho = beam["material"]["young"], beam["material"]["density"]
    beta_l = 4.730040744862704
    exact = beta_l**2 / (2 * math.pi * length**2) * math.sqrt(e * b * h**3 / 12 / (rho * b * h))
    result = model.convergence(max_elements=32, modes=1)
    assert result.reference_hz[0] == pytest.approx(exact, rel=1e-9)
    errors = result.relative_errors[0]
    # O(h⁴): halving the element length divides the error by about 16.
    order = math.log2(errors[-2] / errors[-1])
    assert 3.5 < order < 4.5
    assert abs(result.frequencies_hz[0, -1] - exact) / exact == pytest.approx(errors[-1], rel=1e-9)


def test_bad_arguments_are_model_errors_naming_the_keyword(cli):
    model = ancf_modal.Model.builtin()
    with pytest.raises(ancf_modal.ModelError, match=r"max_elements `1`: must be a whole number from 2 to 256"):
        model.convergence(max_elements=1)
    with pytest.raises(ancf_modal.ModelError, match=r"modes `11`"):
        model.convergence(modes=11)
