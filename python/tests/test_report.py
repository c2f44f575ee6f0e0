"""The HTML report from Python: ``Model.report`` writes the file of
``ancf-modal report`` and ``IdentifyResult.write_html`` the file of
``identify --html``, byte for byte apart from how each was asked for (the
provenance's command line); refusals and warnings are the command line's."""

import html
import re

import pytest

import ancf_modal
from conftest import model_args

# One fixed time for both front ends: the page says when it was written.
EPOCH = "1764000000"
STAMP = "2025-11-24T16:00:00Z"


def _masked(html):
    """The page without the provenance's command line."""
    masked, n = re.subn(r"(<dt>command</dt><dd><code>)[^<]*(</code></dd>)", r"\1…\2", html)
    assert n == 1, "the provenance names the command line once"
    return masked


def _same_page(mine, theirs):
    a, b = mine.read_text(), theirs.read_text()
    assert STAMP in a and STAMP in b
    assert _masked(a) == _masked(b)
    # Python's provenance says it was Python.
    assert "Python package ancf_modal" in a and "Python package" not in b


@pytest.mark.parametrize(
    "name, flags, kwargs",
    [
        # The paper's model with its excitation: identify's sections.
        ("rcbo_free_free", ["--end-time", "0.02"], {"end_time": 0.02}),
        # A model without an excitation, with its pre-stressed modes.
        ("rcbo_prestressed", ["--prestress"], {"prestress": True}),
        # A model that releases something: the switch-off.
        ("rcbo_switch_off", [], {}),
    ],
)
def test_the_report_is_the_command_lines(cli, tmp_path, monkeypatch, name, flags, kwargs):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", EPOCH)
    theirs = tmp_path / "cli.html"
    p = cli.run("report", *model_args(name), "--out", str(theirs), *flags)
    assert p.returncode == 0, p.stderr
    mine = tmp_path / "python.html"
    assert ancf_modal.Model.builtin(name).report(mine, **kwargs) is None
    _same_page(mine, theirs)
    # The page says how to make it again: the call with its keywords.
    command = html.unescape(re.search(r"<dt>command</dt><dd><code>([^<]*)</code>", mine.read_text()).group(1))
    call = command.split(" (Python package", 1)[0]
    assert call == "Model.report(" + ", ".join(
        [f"out={str(mine)!r}".replace("'", '"')] + [f"{k}={v!r}" for k, v in kwargs.items()]
    ) + ")"


def test_an_identify_runs_page_is_identify_html(cli, tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", EPOCH)
    theirs = tmp_path / "cli.html"
    p = cli.run("identify", "--end-time", "0.02", "--html", str(theirs))
    assert p.returncode == 0, p.stderr
    mine = tmp_path / "python.html"
    ancf_modal.Model.builtin().identify(end_time=0.02).write_html(mine)
    _same_page(mine, theirs)


def test_report_refusals_are_the_command_lines(cli, tmp_path):
    model = ancf_modal.Model.builtin("rcbo_prestressed")
    out = tmp_path / "r.html"
    with pytest.raises(ancf_modal.ModelError) as e:
        model.report(out, calibrate=True)
    assert str(e.value) == cli.error("report", *model_args("rcbo_prestressed"), "--out", str(out), "--calibrate")
    assert "calibrate and measured need the impulse experiment" in str(e.value)
    with pytest.raises(ancf_modal.ModelError, match=r"window.*nope"):
        model.report(out, window="nope")
    # The page is HTML whatever its name: another extension is refused,
    # before any computing, as `--plot` refuses one it cannot write.
    pdf = tmp_path / "r.pdf"
    with pytest.raises(ancf_modal.ModelError) as e:
        model.report(pdf)
    assert str(e.value) == f"out `{pdf}`: must end in .html or .htm (the report is one HTML file)"
    assert cli.error("report", "--out", str(pdf)) == "--" + str(e.value)
    assert cli.error("identify", "--html", str(pdf)).startswith(f"--html `{pdf}`: must end in .html")
    with pytest.raises(ancf_modal.ModelError, match=r"^path `.*r.pdf`: must end in .html"):
        ancf_modal.Model.builtin().identify(end_time=0.005).write_html(pdf)
    assert not out.exists() and not pdf.exists(), "a refused report writes nothing"


def test_the_reports_warnings_are_the_command_lines(cli, tmp_path):
    # The paper's blade is 1.1 mm high on 25 mm: its higher modes are past
    # Euler–Bernoulli theory, which `modal` says and so does the report.
    p = cli.run("report", "--end-time", "0.02", "--out", str(tmp_path / "cli.html"))
    theirs = [l.removeprefix("warning: ") for l in p.stderr.splitlines() if l.startswith("warning: ")]
    assert any("beam theory" in w for w in theirs)
    with pytest.warns(ancf_modal.ModelWarning) as caught:
        ancf_modal.Model.builtin().report(tmp_path / "python.html", end_time=0.02)
    assert [str(w.message) for w in caught] == theirs
    assert all(w.category is ancf_modal.ModelWarning for w in caught)
    # The page says them too, first: a mailed report carries its caveats.
    page = (tmp_path / "python.html").read_text()
    assert '<section id="warnings"' in page
    assert page.index('id="warnings"') < page.index('id="assembly"')
    section = page.split('<section id="warnings"', 1)[1].split("</section>", 1)[0]
    assert [html.unescape(li) for li in re.findall(r"<li>(.*?)</li>", section)] == theirs
